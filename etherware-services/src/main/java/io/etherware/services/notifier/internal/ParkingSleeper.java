package io.etherware.services.notifier.internal;

import io.etherware.core.time.NodeClock;
import java.util.concurrent.locks.LockSupport;

/**
 * Sleeps to an absolute deadline with {@link LockSupport#parkNanos}, optionally waking
 * {@code spinNs} early and spinning on the clock for the rest, which a timer wake-up cannot match
 * for accuracy (a few µs instead of tens).
 *
 * <p>The spin is bounded per release by {@code spinNs}: it starts no earlier than {@code spinNs}
 * before the deadline and never outlasts it, so at real-time priority it takes at most that much
 * of its CPU per release. A late wake-up shortens the spin; it never extends it.
 *
 * <p>Called only on the Notifier thread.
 */
public final class ParkingSleeper implements Sleeper {

    private final NodeClock clock;
    private final long spinNs;

    public ParkingSleeper(NodeClock clock, long spinNs) {
        if (spinNs < 0) {
            throw new IllegalArgumentException("spinNs=" + spinNs + " must not be negative");
        }
        this.clock = clock;
        this.spinNs = spinNs;
    }

    @Override
    public void sleepUntil(long deadlineNs) {
        if (deadlineNs == Long.MAX_VALUE) {
            LockSupport.park(this);
            Thread.interrupted(); // a stray interrupt would make every later park return at once
            return;
        }
        long wakeNs = deadlineNs - spinNs;
        long nowNs = clock.nanoTime();
        if (nowNs < wakeNs) {
            LockSupport.parkNanos(this, wakeNs - nowNs);
            Thread.interrupted();
            nowNs = clock.nanoTime();
            if (nowNs < wakeNs) {
                return; // unparked early: the caller looks again at what is due
            }
        }
        // Bounded: the loop ends at the deadline, at most spinNs after it began.
        while (spinNs > 0 && nowNs < deadlineNs) {
            Thread.onSpinWait();
            nowNs = clock.nanoTime();
        }
    }
}
