package io.etherware.services.notifier;

import io.etherware.core.message.Criticality;
import io.etherware.core.message.Profile;
import io.etherware.core.message.QoS;
import java.util.Objects;

/**
 * What a component asks of the {@link Notifier}: Ticks to {@code target} with {@code qos}, either
 * periodic ({@code qos.periodNs() > 0}, releases at {@code firstReleaseNs + k * periodNs}) or
 * one-shot ({@code qos.periodNs() == 0}, one release at {@code firstReleaseNs}). Immutable.
 *
 * <p>Build one with {@link #periodic} or {@link #oneShot} and adjust it with the {@code with…}
 * methods; the constructor checks every field and names the wrong one.
 *
 * @param name           unique among the subscriptions of one Notifier: 1 to {@value #MAX_NAME_LENGTH}
 *                       characters, no control characters
 * @param target         the profile the Ticks are sent to (exact, or a query that resolves to one
 *                       component); {@link Notifier#retarget} changes it at runtime
 * @param qos            the QoS of every Tick; its period is the subscription's period (0: one-shot);
 *                       its deadline defaults to the period, relative to each release
 * @param firstReleaseNs the first release on the Notifier's monotonic clock, or {@link #UNSET}: one
 *                       period after subscribing (periodic) or at once (one-shot)
 * @param maxLatenessNs  periodic only: a release that the Notifier reaches this late or later is
 *                       skipped instead of sent, in 1..period (default half the period, so two Ticks
 *                       of one subscription are never sent less than half a period apart); 0 for a
 *                       one-shot, which is always sent, however late
 * @param backPressure   whether a release is skipped while the target, a local component, has not
 *                       finished a single message since the previous Tick was sent to it (it is
 *                       stalled or still busy: another Tick would only queue up behind it and
 *                       reach it in a burst when it recovers)
 */
public record Subscription(String name, Profile target, QoS qos, long firstReleaseNs, long maxLatenessNs,
                           boolean backPressure) {

    /** {@link #firstReleaseNs} not given. */
    public static final long UNSET = Long.MIN_VALUE;
    /** Longest subscription name. */
    public static final int MAX_NAME_LENGTH = 256;

    /**
     * Checks every field.
     *
     * @throws NullPointerException     if {@code name}, {@code target} or {@code qos} is null
     * @throws IllegalArgumentException if the name is blank, too long or has control characters, or
     *                                  {@code maxLatenessNs} is outside 1..period (periodic) or not 0
     *                                  (one-shot)
     */
    public Subscription {
        requireValidName(name);
        Objects.requireNonNull(target, "target");
        Objects.requireNonNull(qos, "qos");
        if (qos.hasPeriod()) {
            if (maxLatenessNs < 1 || maxLatenessNs > qos.periodNs()) {
                throw new IllegalArgumentException("subscription '" + name + "': maxLatenessNs=" + maxLatenessNs
                        + " must be in 1..periodNs=" + qos.periodNs());
            }
        } else if (maxLatenessNs != 0) {
            throw new IllegalArgumentException("subscription '" + name + "': maxLatenessNs=" + maxLatenessNs
                    + " must be 0 for a one-shot (periodNs=0): a one-shot is always sent");
        }
    }

    /**
     * Ticks every {@code periodNs} to {@code target}, with QoS criticality {@code criticality},
     * period and deadline {@code periodNs}, first release one period after subscribing, lateness
     * limit half a period, back-pressure on.
     *
     * @param name        the subscription's name, unique on its Notifier
     * @param target      where the Ticks go
     * @param criticality the Ticks' criticality
     * @param periodNs    the period in nanoseconds, &gt; 0
     * @return the subscription
     * @throws IllegalArgumentException if {@code periodNs} &lt;= 0 or the name is not valid
     */
    public static Subscription periodic(String name, Profile target, Criticality criticality, long periodNs) {
        Objects.requireNonNull(criticality, "criticality");
        if (periodNs <= 0) {
            throw new IllegalArgumentException("subscription '" + name + "': periodNs=" + periodNs + " must be > 0");
        }
        return new Subscription(name, target, QoS.periodic(criticality, periodNs), UNSET, Math.max(1, periodNs / 2),
                true);
    }

    /**
     * One Tick to {@code target} at {@code releaseNs} on the Notifier's monotonic clock (at once if
     * that is past), with QoS criticality {@code criticality} and no deadline.
     *
     * @param name        the subscription's name, unique on its Notifier
     * @param target      where the Tick goes
     * @param criticality the Tick's criticality
     * @param releaseNs   the release on the Notifier's monotonic clock (nanoseconds), or
     *                    {@link #UNSET} for at once
     * @return the subscription
     * @throws IllegalArgumentException if the name is not valid
     */
    public static Subscription oneShot(String name, Profile target, Criticality criticality, long releaseNs) {
        Objects.requireNonNull(criticality, "criticality");
        return new Subscription(name, target, QoS.of(criticality), releaseNs, 0, true);
    }

    /**
     * Whether this is a one-shot subscription.
     *
     * @return true if its QoS has no period
     */
    public boolean isOneShot() {
        return !qos.hasPeriod();
    }

    /**
     * The period of the releases.
     *
     * @return the period in nanoseconds, 0 for a one-shot
     */
    public long periodNs() {
        return qos.periodNs();
    }

    /**
     * This subscription with its first release at another time.
     *
     * @param releaseNs the first release (periodic: {@code t0} of the grid) on the Notifier's
     *                  monotonic clock, in nanoseconds
     * @return a copy starting then
     */
    public Subscription startingAt(long releaseNs) {
        return new Subscription(name, target, qos, releaseNs, maxLatenessNs, backPressure);
    }

    /**
     * This subscription with another relative deadline in each Tick's QoS.
     *
     * @param deadlineNs the deadline after each release, in nanoseconds; 0 for none
     * @return a copy with that deadline
     * @throws IllegalArgumentException if {@code deadlineNs} is negative
     */
    public Subscription withDeadlineNs(long deadlineNs) {
        return new Subscription(name, target, qos.withDeadlineNs(deadlineNs), firstReleaseNs, maxLatenessNs,
                backPressure);
    }

    /**
     * This subscription with the receiver's worst-case handling time in each Tick's QoS.
     *
     * @param wcetNs the worst-case handling time in nanoseconds; 0 for unknown
     * @return a copy with that handling time
     * @throws IllegalArgumentException if {@code wcetNs} is negative
     */
    public Subscription withWcetNs(long wcetNs) {
        return new Subscription(name, target, qos.withWcetNs(wcetNs), firstReleaseNs, maxLatenessNs, backPressure);
    }

    /**
     * This subscription with another lateness limit (see {@link #maxLatenessNs}).
     *
     * @param newMaxLatenessNs the limit in nanoseconds: 1..period for a periodic subscription, 0
     *                         for a one-shot
     * @return a copy with that limit
     * @throws IllegalArgumentException if {@code newMaxLatenessNs} is out of range
     */
    public Subscription withMaxLatenessNs(long newMaxLatenessNs) {
        return new Subscription(name, target, qos, firstReleaseNs, newMaxLatenessNs, backPressure);
    }

    /**
     * This subscription with back-pressure on or off (see {@link #backPressure}).
     *
     * @param enabled true to skip releases while the local target has not finished a message since
     *                the previous Tick
     * @return a copy with that setting
     */
    public Subscription withBackPressure(boolean enabled) {
        return new Subscription(name, target, qos, firstReleaseNs, maxLatenessNs, enabled);
    }

    /**
     * This subscription sending to another profile; to move a running subscription, use
     * {@link Notifier#retarget}.
     *
     * @param newTarget the profile the Ticks go to
     * @return a copy with that target
     */
    public Subscription withTarget(Profile newTarget) {
        return new Subscription(name, newTarget, qos, firstReleaseNs, maxLatenessNs, backPressure);
    }

    static void requireValidName(String name) {
        Objects.requireNonNull(name, "name");
        if (name.isBlank() || name.length() > MAX_NAME_LENGTH) {
            throw new IllegalArgumentException("subscription name '" + name + "' must be 1.." + MAX_NAME_LENGTH
                    + " characters and not blank");
        }
        for (int i = 0; i < name.length(); i++) {
            if (Character.isISOControl(name.charAt(i))) {
                throw new IllegalArgumentException("subscription name '" + name.replaceAll("\\p{Cntrl}", "?")
                        + "' must not contain control characters (at index " + i + ")");
            }
        }
    }
}
