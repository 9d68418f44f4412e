package io.etherware.services.notifier;

import io.etherware.rt.stats.LatencySnapshot;
import java.util.Objects;

/**
 * One subscription's accounting since it was added, read at one moment (each counter is exact;
 * they are not read atomically together). Immutable.
 *
 * @param subscription     the subscription, with its current target and its actual first release
 * @param ticksSent        Ticks handed to the kernel
 * @param skippedLate      releases skipped because the Notifier reached them too late: after the
 *                         next release was due, or past {@link Subscription#maxLatenessNs()}
 * @param skippedBusy      releases skipped by back-pressure: the receiver had not finished a
 *                         message since the previous Tick
 * @param skippedUndeliverable releases skipped because the target resolved to nothing or the kernel
 *                         refused the Tick (logged once per episode)
 * @param nextSequence     the index k of the next release ({@code t0 + k * period})
 * @param latenessNs       actual send time minus scheduled release time of every Tick sent, in
 *                         nanoseconds of the Notifier's clock, 2 significant digits, values over
 *                         10 s recorded as 10 s
 */
public record SubscriptionStats(Subscription subscription, long ticksSent, long skippedLate, long skippedBusy,
                                long skippedUndeliverable, long nextSequence, LatencySnapshot latenessNs) {

    /**
     * Checks that the subscription and the lateness snapshot are given.
     *
     * @throws NullPointerException if {@code subscription} or {@code latenessNs} is null
     */
    public SubscriptionStats {
        Objects.requireNonNull(subscription, "subscription");
        Objects.requireNonNull(latenessNs, "latenessNs");
    }

    /**
     * The subscription's name.
     *
     * @return {@code subscription().name()}
     */
    public String name() {
        return subscription.name();
    }

    /**
     * Every release that was not sent, for whatever reason.
     *
     * @return {@code skippedLate + skippedBusy + skippedUndeliverable}
     */
    public long skippedReleases() {
        return skippedLate + skippedBusy + skippedUndeliverable;
    }
}
