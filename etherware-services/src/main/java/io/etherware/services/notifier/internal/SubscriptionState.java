package io.etherware.services.notifier.internal;

import io.etherware.core.message.Profile;
import io.etherware.core.message.QoS;
import io.etherware.rt.stats.LatencyRecorder;
import io.etherware.services.notifier.Subscription;
import io.etherware.services.notifier.SubscriptionStats;
import java.util.concurrent.atomic.AtomicLong;

/**
 * One subscription inside the Notifier: its fixed release grid ({@code t0 + k * period}), where
 * it stands on it, its current target and its accounting.
 *
 * <p>Threading: the release fields and the {@code record…} methods belong to the Notifier thread
 * (single writer, no locks, no allocation); {@link #retarget}, {@link #cancel} and the readers
 * may be called from any thread; {@link #stats()} is serialized here.
 */
public final class SubscriptionState {

    /** Lateness above this is recorded as this: 10 s. */
    static final long HIGHEST_TRACKABLE_NS = 10_000_000_000L;
    private static final int SIGNIFICANT_DIGITS = 2;

    private final Subscription subscription;
    private final long order;
    private final long t0Ns;
    private final long periodNs;
    private volatile Profile target;
    private volatile boolean cancelled;

    // Notifier thread only.
    private long nextSequence;
    private long nextReleaseNs;
    private Object lastReceiver;
    private long lastReceiverCount;
    private boolean undeliverableEpisode;

    // Single writer (the Notifier thread), any reader.
    private final AtomicLong ticksSent = new AtomicLong();
    private final AtomicLong skippedLate = new AtomicLong();
    private final AtomicLong skippedBusy = new AtomicLong();
    private final AtomicLong skippedUndeliverable = new AtomicLong();
    private final AtomicLong publishedNextSequence = new AtomicLong();
    private final LatencyRecorder lateness = new LatencyRecorder(HIGHEST_TRACKABLE_NS, SIGNIFICANT_DIGITS);

    /**
     * @param subscription the subscription with its first release resolved (never
     *                     {@link Subscription#UNSET})
     * @param order        tie-break among subscriptions released at the same time: lower first
     * @param nowNs        the clock when subscribing: a periodic grid whose {@code t0} is past
     *                     starts at its first release not before now, keeping its phase
     */
    public SubscriptionState(Subscription subscription, long order, long nowNs) {
        if (subscription.firstReleaseNs() == Subscription.UNSET) {
            throw new IllegalArgumentException("subscription '" + subscription.name() + "' has no first release");
        }
        this.subscription = subscription;
        this.order = order;
        this.t0Ns = subscription.firstReleaseNs();
        this.periodNs = subscription.periodNs();
        this.target = subscription.target();
        long firstSequence = 0;
        if (periodNs > 0 && t0Ns < nowNs) {
            firstSequence = ceilDiv(nowNs - t0Ns, periodNs);
        }
        this.nextSequence = firstSequence;
        this.nextReleaseNs = t0Ns + firstSequence * periodNs;
        publishedNextSequence.setRelease(firstSequence);
    }

    public String name() {
        return subscription.name();
    }

    public Subscription subscription() {
        return subscription.withTarget(target);
    }

    long order() {
        return order;
    }

    long t0Ns() {
        return t0Ns;
    }

    long periodNs() {
        return periodNs;
    }

    // ---------------------------------------------------------------- any thread

    /** Sends the next Ticks to {@code newTarget}. */
    public void retarget(Profile newTarget) {
        target = newTarget;
    }

    public Profile target() {
        return target;
    }

    /** No Tick of this subscription is released once the Notifier thread sees this. */
    public void cancel() {
        cancelled = true;
    }

    public boolean isCancelled() {
        return cancelled;
    }

    /** Everything recorded since the subscription was added. */
    public synchronized SubscriptionStats stats() {
        return new SubscriptionStats(subscription(), ticksSent.get(), skippedLate.get(), skippedBusy.get(),
                skippedUndeliverable.get(), publishedNextSequence.get(), lateness.snapshot());
    }

    // ---------------------------------------------------------------- Notifier thread

    long nextReleaseNs() {
        return nextReleaseNs;
    }

    long nextSequence() {
        return nextSequence;
    }

    /**
     * Moves past the release of {@code sequence} (and every earlier one): the next release is the
     * following grid point. A one-shot has none.
     */
    void advancePast(long sequence) {
        nextSequence = sequence + 1;
        nextReleaseNs = periodNs > 0 ? t0Ns + nextSequence * periodNs : Long.MAX_VALUE;
    }

    /** Makes the position on the grid readable, once the release's outcome is counted. */
    void publishProgress() {
        publishedNextSequence.setRelease(nextSequence);
    }

    boolean isFinished() {
        return nextReleaseNs == Long.MAX_VALUE;
    }

    QoS qos() {
        return subscription.qos();
    }

    long maxLatenessNs() {
        return subscription.maxLatenessNs();
    }

    boolean backPressure() {
        return subscription.backPressure();
    }

    /**
     * Back-pressure: whether {@code receiver}, whose finished-message count is
     * {@code finishedCount}, has finished nothing since the previous Tick was sent to it.
     */
    boolean isReceiverBusy(Object receiver, long finishedCount) {
        return receiver == lastReceiver && finishedCount == lastReceiverCount;
    }

    /** A Tick is about to go to {@code receiver} (null: not a local component). */
    void rememberReceiver(Object receiver, long finishedCount) {
        lastReceiver = receiver;
        lastReceiverCount = finishedCount;
    }

    void recordSent(long latenessNs) {
        lateness.record(latenessNs);
        increment(ticksSent);
    }

    void recordSkippedLate(long releases) {
        skippedLate.setRelease(skippedLate.getPlain() + releases);
    }

    void recordSkippedBusy() {
        increment(skippedBusy);
    }

    /** Counts an undeliverable release; true if it starts an episode (worth one log line). */
    boolean recordUndeliverable() {
        increment(skippedUndeliverable);
        boolean starts = !undeliverableEpisode;
        undeliverableEpisode = true;
        return starts;
    }

    /** A Tick went out: true if that ends an episode of undeliverable releases. */
    boolean endUndeliverableEpisode() {
        boolean ends = undeliverableEpisode;
        undeliverableEpisode = false;
        return ends;
    }

    private static void increment(AtomicLong counter) {
        counter.setRelease(counter.getPlain() + 1);
    }

    private static long ceilDiv(long dividend, long divisor) {
        return Math.ceilDiv(dividend, divisor);
    }
}
