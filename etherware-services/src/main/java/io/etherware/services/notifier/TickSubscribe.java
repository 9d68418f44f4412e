package io.etherware.services.notifier;

import io.etherware.core.message.Contents;
import io.etherware.core.message.Criticality;
import io.etherware.core.message.Profile;
import java.util.Objects;

/**
 * A request to the Notifier's component ({@code notifier.subscribe}): Ticks for the sender, or for
 * {@code target}. The Notifier answers with a {@link NotifierReply}. Immutable.
 *
 * <pre>{@code
 * context.request(Notifier.profileFor(nodeId), TickSubscribe.periodic(Criticality.HIGH, 15_000_000L));
 * }</pre>
 *
 * @param name           the subscription's name, or null for the target's profile text
 * @param target         where the Ticks go, or null for the request's sender
 * @param criticality    the Ticks' criticality
 * @param periodNs       the period, or 0 for a one-shot
 * @param deadlineNs     each Tick's relative deadline, or 0 for the period (none for a one-shot)
 * @param wcetNs         the receiver's worst-case handling time for the Ticks' QoS, or 0
 * @param firstReleaseNs the first release on the Notifier node's monotonic clock, or null: one
 *                       period from now (periodic), at once (one-shot)
 * @param maxLatenessNs  see {@link Subscription#maxLatenessNs()}; 0 for the default
 * @param backPressure   see {@link Subscription#backPressure()}
 */
public record TickSubscribe(String name, Profile target, Criticality criticality, long periodNs, long deadlineNs,
                            long wcetNs, Long firstReleaseNs, long maxLatenessNs, boolean backPressure)
        implements Contents {

    /**
     * Checks that the criticality is given; the other fields are checked by the Notifier, which
     * refuses a bad request with a {@link NotifierReply} naming the field.
     *
     * @throws NullPointerException if {@code criticality} is null
     */
    public TickSubscribe {
        Objects.requireNonNull(criticality, "criticality");
    }

    /**
     * Periodic Ticks for the sender, named after it, deadline = period, lateness limit half a
     * period, back-pressure on, first release one period after the Notifier accepts it.
     *
     * @param criticality the Ticks' criticality
     * @param periodNs    the period in nanoseconds, &gt; 0 (checked by the Notifier)
     * @return the request
     */
    public static TickSubscribe periodic(Criticality criticality, long periodNs) {
        return new TickSubscribe(null, null, criticality, periodNs, 0, 0, null, 0, true);
    }

    /**
     * One Tick for the sender at {@code releaseNs} (at once if that is past), named after it.
     *
     * @param criticality the Tick's criticality
     * @param releaseNs   the release on the Notifier node's monotonic clock, in nanoseconds
     * @return the request
     */
    public static TickSubscribe oneShot(Criticality criticality, long releaseNs) {
        return new TickSubscribe(null, null, criticality, 0, 0, 0, releaseNs, 0, true);
    }

    /**
     * This request under an explicit subscription name, e.g. for a second subscription of one
     * component.
     *
     * @param newName the name (see {@link Subscription#name()} for the rules), or null for the
     *                target's profile text
     * @return a copy with that name
     */
    public TickSubscribe named(String newName) {
        return new TickSubscribe(newName, target, criticality, periodNs, deadlineNs, wcetNs, firstReleaseNs,
                maxLatenessNs, backPressure);
    }

    /**
     * This request sending the Ticks to another profile than the sender's.
     *
     * @param newTarget where the Ticks go, or null for the request's sender
     * @return a copy with that target
     */
    public TickSubscribe to(Profile newTarget) {
        return new TickSubscribe(name, newTarget, criticality, periodNs, deadlineNs, wcetNs, firstReleaseNs,
                maxLatenessNs, backPressure);
    }

    /**
     * This request with its first release at {@code releaseNs}.
     *
     * @param releaseNs the first release (periodic: {@code t0} of the grid) on the Notifier node's
     *                  monotonic clock, in nanoseconds
     * @return a copy starting then
     */
    public TickSubscribe startingAt(long releaseNs) {
        return new TickSubscribe(name, target, criticality, periodNs, deadlineNs, wcetNs, releaseNs, maxLatenessNs,
                backPressure);
    }

    /**
     * This request with another lateness limit (see {@link Subscription#maxLatenessNs()}).
     *
     * @param newMaxLatenessNs the limit in nanoseconds, 1..period; 0 for the default (half the
     *                         period); must be 0 for a one-shot
     * @return a copy with that limit
     */
    public TickSubscribe withMaxLatenessNs(long newMaxLatenessNs) {
        return new TickSubscribe(name, target, criticality, periodNs, deadlineNs, wcetNs, firstReleaseNs,
                newMaxLatenessNs, backPressure);
    }

    /**
     * This request with back-pressure on or off (see {@link Subscription#backPressure()}).
     *
     * @param enabled true (default) to skip releases while the target has not finished a message
     *                since the previous Tick
     * @return a copy with that setting
     */
    public TickSubscribe withBackPressure(boolean enabled) {
        return new TickSubscribe(name, target, criticality, periodNs, deadlineNs, wcetNs, firstReleaseNs,
                maxLatenessNs, enabled);
    }

    /**
     * This request with another relative deadline in each Tick's QoS.
     *
     * @param newDeadlineNs the deadline after each release in nanoseconds, &gt;= 0; 0 for the
     *                      period (none for a one-shot)
     * @return a copy with that deadline
     */
    public TickSubscribe withDeadlineNs(long newDeadlineNs) {
        return new TickSubscribe(name, target, criticality, periodNs, newDeadlineNs, wcetNs, firstReleaseNs,
                maxLatenessNs, backPressure);
    }

    /**
     * The subscription this request asks for.
     *
     * @throws IllegalArgumentException naming the field, if the request is not valid
     */
    Subscription toSubscription(Profile sender) {
        Profile to = target != null ? target : sender;
        if (to == null) {
            throw new IllegalArgumentException("target=null and the request has no sender to send Ticks to");
        }
        String subscriptionName = name != null ? name : to.toString();
        Subscription subscription;
        if (periodNs > 0) {
            subscription = Subscription.periodic(subscriptionName, to, criticality, periodNs);
            if (maxLatenessNs != 0) {
                subscription = subscription.withMaxLatenessNs(maxLatenessNs);
            }
            if (firstReleaseNs != null) {
                subscription = subscription.startingAt(firstReleaseNs);
            }
        } else if (periodNs == 0) {
            if (maxLatenessNs != 0) {
                throw new IllegalArgumentException("maxLatenessNs=" + maxLatenessNs + " must be 0 for a one-shot");
            }
            subscription = Subscription.oneShot(subscriptionName, to, criticality,
                    firstReleaseNs != null ? firstReleaseNs : Subscription.UNSET);
        } else {
            throw new IllegalArgumentException("periodNs=" + periodNs + " must be >= 0 (0: one-shot)");
        }
        if (deadlineNs != 0) {
            subscription = subscription.withDeadlineNs(deadlineNs);
        }
        return subscription.withWcetNs(wcetNs).withBackPressure(backPressure);
    }
}
