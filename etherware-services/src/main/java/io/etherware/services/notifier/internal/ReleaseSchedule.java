package io.etherware.services.notifier.internal;

import io.etherware.core.component.Shell;
import io.etherware.core.kernel.Endpoint;
import io.etherware.core.kernel.Kernel;
import io.etherware.core.kernel.ProfileResolutionException;
import io.etherware.core.message.Message;
import io.etherware.core.message.Profile;
import io.etherware.core.message.Tick;
import io.etherware.core.time.NodeClock;
import java.util.Comparator;
import java.util.PriorityQueue;
import java.util.concurrent.locks.LockSupport;
import java.util.function.Consumer;
import org.slf4j.Logger;
import org.slf4j.LoggerFactory;

/**
 * The Notifier's releases: one priority queue of the subscriptions' next release times, served by
 * one thread, and the rule for each release — send the Tick, or skip and count it.
 *
 * <p>The rule, per release due at {@code r = t0 + k * period} and reached at {@code now}:
 * <ol>
 *   <li>If later releases are due as well (the thread woke after the next one), the older ones are
 *       skipped and counted: only the latest due release may still go out. Never a burst of
 *       catch-up Ticks (design decision 7; ROS 2 timers are known to burst here).</li>
 *   <li>If even the latest is {@code maxLatenessNs} late or more, it is skipped too, so two Ticks
 *       of one subscription never go out less than {@code period - maxLatenessNs} apart.</li>
 *   <li>If the target does not resolve, the release is skipped and counted (logged once per
 *       episode).</li>
 *   <li>With back-pressure, if the target is a local component that has finished no message since
 *       the previous Tick was sent to it, the release is skipped and counted.</li>
 *   <li>Otherwise the Tick {@code (r, k, period)} goes to the kernel; its lateness
 *       {@code send time - r} is recorded.</li>
 * </ol>
 * Release times are computed from {@code k}, never accumulated, so they do not drift.
 *
 * <p>Threading: {@link #add} and {@link #fireDue} on the Notifier thread only;
 * {@link #awaitNotSending} from any other thread.
 */
public final class ReleaseSchedule {

    private static final Logger LOG = LoggerFactory.getLogger(ReleaseSchedule.class);

    private static final Comparator<SubscriptionState> BY_RELEASE_THEN_ORDER =
            Comparator.comparingLong(SubscriptionState::nextReleaseNs).thenComparingLong(SubscriptionState::order);

    private final Kernel kernel;
    private final NodeClock clock;
    private final Profile sender;
    private final PriorityQueue<SubscriptionState> queue = new PriorityQueue<>(16, BY_RELEASE_THEN_ORDER);
    /** The subscription whose release is being decided and sent; see {@link #awaitNotSending}. */
    private volatile SubscriptionState sending;
    private volatile Thread owner;

    /**
     * @param kernel where Ticks go, and whose registry resolves their targets
     * @param clock  the Notifier's clock: release and send times
     * @param sender the Notifier's profile, the sender of every Tick
     */
    public ReleaseSchedule(Kernel kernel, NodeClock clock, Profile sender) {
        this.kernel = kernel;
        this.clock = clock;
        this.sender = sender;
    }

    /** Called once by the Notifier thread before it serves: {@link #awaitNotSending} must not wait for itself. */
    public void claimThread() {
        owner = Thread.currentThread();
    }

    /** Notifier thread: schedules a new subscription. */
    public void add(SubscriptionState state) {
        if (!state.isCancelled()) {
            queue.add(state);
        }
    }

    /** Notifier thread: the number of subscriptions queued (cancelled ones until they surface). */
    public int size() {
        return queue.size();
    }

    /**
     * Notifier thread: decides every release due now, in release order, and returns the next
     * release time, or {@link Long#MAX_VALUE} when nothing is scheduled.
     *
     * @param finished called with each subscription that will not release again (a fired one-shot)
     */
    public long fireDue(Consumer<SubscriptionState> finished) {
        while (true) {
            SubscriptionState state = queue.peek();
            if (state == null) {
                return Long.MAX_VALUE;
            }
            if (state.isCancelled()) {
                queue.poll();
                continue;
            }
            long nowNs = clock.nanoTime();
            if (state.nextReleaseNs() > nowNs) {
                return state.nextReleaseNs();
            }
            queue.poll();
            release(state, nowNs);
            if (state.isFinished()) {
                finished.accept(state);
            } else {
                queue.add(state);
            }
        }
    }

    private void release(SubscriptionState state, long nowNs) {
        sending = state;
        try {
            decide(state, nowNs);
        } finally {
            // Published before 'sending' clears: a reader that waited for us sees the whole outcome.
            state.publishProgress();
            sending = null;
        }
    }

    private void decide(SubscriptionState state, long nowNs) {
        long periodNs = state.periodNs();
        long sequence = state.nextSequence();
        long releaseNs = state.nextReleaseNs();
        if (periodNs > 0) {
            long alsoDue = (nowNs - releaseNs) / periodNs;
            if (alsoDue > 0) {
                state.recordSkippedLate(alsoDue);
                sequence += alsoDue;
                releaseNs = state.t0Ns() + sequence * periodNs;
            }
            if (nowNs - releaseNs >= state.maxLatenessNs()) {
                state.recordSkippedLate(1);
                state.advancePast(sequence);
                return;
            }
        }
        state.advancePast(sequence);
        // Read after publishing 'sending': a canceller or retargeter that missed us waits for us.
        if (state.isCancelled()) {
            return;
        }
        try {
            send(state, sequence, releaseNs, periodNs);
        } catch (RuntimeException e) {
            // The node is not started, or a route or the registry threw: count it and run on; one
            // failing release must not stop the thread that serves every subscription.
            state.rememberReceiver(null, 0);
            if (state.recordUndeliverable()) {
                LOG.warn("notifier {}: subscription '{}': Tick #{} to '{}' failed: {}; further failures are counted"
                        + " until a Tick goes out", sender, state.name(), sequence, state.target(), e.toString(), e);
            }
        }
    }

    private void send(SubscriptionState state, long sequence, long releaseNs, long periodNs) {
        Profile target = state.target();
        Endpoint endpoint;
        try {
            endpoint = kernel.registry().resolve(target);
        } catch (ProfileResolutionException e) {
            if (state.recordUndeliverable()) {
                LOG.warn("notifier {}: subscription '{}' skips its releases from #{} on: target '{}' does not resolve"
                        + " ({}); they are counted, not sent, until it does", sender, state.name(), sequence, target,
                        e.getMessage());
            }
            return;
        }
        if (state.backPressure() && endpoint instanceof Endpoint.Local local) {
            Shell shell = local.shell();
            long finished = shell.handledCount() + shell.failedCount();
            if (state.isReceiverBusy(shell, finished)) {
                state.recordSkippedBusy();
                return;
            }
            state.rememberReceiver(shell, finished);
        } else {
            state.rememberReceiver(null, 0);
        }
        long sendNs = clock.nanoTime();
        var tick = new Message(target, sender, clock.epochNanos(), state.qos(),
                new Tick(releaseNs, sequence, periodNs), kernel.newMessageId(), null);
        kernel.send(tick);
        state.recordSent(sendNs - releaseNs);
        if (state.endUndeliverableEpisode()) {
            LOG.info("notifier {}: subscription '{}' delivers again to '{}' from release #{}", sender, state.name(),
                    target, sequence);
        }
    }

    /**
     * Any thread but the Notifier's: waits until the Notifier thread is not deciding or sending a
     * release of {@code state}. Call after {@link SubscriptionState#cancel} or
     * {@link SubscriptionState#retarget}: afterwards no Tick goes out under the old settings. The
     * wait is the length of one {@link Kernel#send}, which does not block; it parks rather than
     * spins, so a caller at a higher priority cannot starve the Notifier.
     */
    public void awaitNotSending(SubscriptionState state) {
        if (Thread.currentThread() == owner) {
            return;
        }
        while (sending == state) {
            LockSupport.parkNanos(10_000);
        }
    }
}
