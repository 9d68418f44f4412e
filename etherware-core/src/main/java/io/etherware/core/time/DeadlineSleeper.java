package io.etherware.core.time;

import java.util.Objects;
import java.util.concurrent.locks.LockSupport;

/**
 * How a periodic thread sleeps to an absolute time on its {@link NodeClock} (design decision 7:
 * {@code next += periodNs}, then sleep to {@code next}). A seam: the real-time module supplies one
 * that sleeps in the kernel to the absolute time ({@code clock_nanosleep} with
 * {@code TIMER_ABSTIME}); tests and other platforms use {@link #parking}.
 *
 * <p>An instance belongs to one thread. It may return early (the caller re-reads its clock and
 * loops); it should not return much later than the deadline.
 */
@FunctionalInterface
public interface DeadlineSleeper {

    /**
     * Sleeps until {@code deadlineNs} on the sleeper's clock, or returns at once if it has passed.
     *
     * @param deadlineNs the absolute time to wake at, in nanoseconds of the clock's
     *                   {@link NodeClock#nanoTime()}
     */
    void sleepUntil(long deadlineNs);

    /**
     * {@link LockSupport#parkNanos} for the time left on {@code clock}: portable, and ended early by
     * {@link LockSupport#unpark} or an interrupt (whose flag it leaves set).
     *
     * @param clock the clock the deadlines are read on
     * @return a sleeper that parks the calling thread until each deadline
     */
    static DeadlineSleeper parking(NodeClock clock) {
        Objects.requireNonNull(clock, "clock");
        return deadlineNs -> {
            long leftNs = deadlineNs - clock.nanoTime();
            if (leftNs > 0) {
                LockSupport.parkNanos(leftNs);
            }
        };
    }
}
