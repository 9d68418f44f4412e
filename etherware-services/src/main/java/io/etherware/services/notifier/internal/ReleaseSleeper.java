package io.etherware.services.notifier.internal;

import io.etherware.core.time.DeadlineSleeper;
import io.etherware.core.time.NodeClock;
import java.util.concurrent.locks.LockSupport;

/**
 * Sleeps to an absolute release time: parks with {@link LockSupport#parkNanos} (so an unpark ends
 * the wait), and, given a kernel sleeper, parks only until {@value #KERNEL_WINDOW_NS} ns before the
 * release and sleeps the rest in the kernel to the absolute time ({@code clock_nanosleep} with
 * {@code TIMER_ABSTIME}, as cyclictest does). Optionally it wakes {@code spinNs} early and spins on
 * the clock for the rest, which a timer wake-up cannot match for accuracy (a few µs instead of tens).
 *
 * <p>Neither a kernel sleep nor the spin after it is ended by an unpark, so an unpark that comes
 * within the window (a new subscription, the Notifier closing) takes effect at most {@value
 * #KERNEL_WINDOW_NS} ns plus {@code spinNs} late (its permit outlives the sleep: the next park
 * returns at once).
 *
 * <p>The spin is bounded per release by {@code spinNs}: it starts no earlier than {@code spinNs}
 * before the deadline and never outlasts it, so at real-time priority it takes at most that much
 * of its CPU per release. A late wake-up shortens the spin; it never extends it.
 *
 * <p>Called only on the Notifier thread.
 */
public final class ReleaseSleeper implements Sleeper {

    /** The stretch before a release slept in the kernel, when there is a kernel sleeper: 1 ms. */
    public static final long KERNEL_WINDOW_NS = 1_000_000L;

    private final NodeClock clock;
    private final long spinNs;
    private final DeadlineSleeper kernelSleeper;

    /**
     * @param kernelSleeper sleeps to an absolute time of {@code clock} in the kernel, or null to park only
     */
    public ReleaseSleeper(NodeClock clock, long spinNs, DeadlineSleeper kernelSleeper) {
        if (spinNs < 0) {
            throw new IllegalArgumentException("spinNs=" + spinNs + " must not be negative");
        }
        this.clock = clock;
        this.spinNs = spinNs;
        this.kernelSleeper = kernelSleeper;
    }

    @Override
    public void sleepUntil(long deadlineNs) {
        if (deadlineNs == Long.MAX_VALUE) {
            LockSupport.park(this);
            Thread.interrupted(); // a stray interrupt would make every later park return at once
            return;
        }
        long wakeNs = deadlineNs - spinNs;
        long parkUntilNs = kernelSleeper == null ? wakeNs : wakeNs - KERNEL_WINDOW_NS;
        long nowNs = clock.nanoTime();
        if (nowNs < parkUntilNs) {
            LockSupport.parkNanos(this, parkUntilNs - nowNs);
            Thread.interrupted();
            nowNs = clock.nanoTime();
            if (nowNs < parkUntilNs) {
                return; // unparked early: the caller looks again at what is due
            }
        }
        if (kernelSleeper != null && nowNs < wakeNs) {
            kernelSleeper.sleepUntil(wakeNs);
            nowNs = clock.nanoTime();
        }
        // Bounded: the loop ends at the deadline, at most spinNs after it began.
        while (spinNs > 0 && nowNs < deadlineNs) {
            Thread.onSpinWait();
            nowNs = clock.nanoTime();
        }
    }
}
