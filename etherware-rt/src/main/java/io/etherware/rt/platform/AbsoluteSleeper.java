package io.etherware.rt.platform;

import io.etherware.core.time.DeadlineSleeper;
import io.etherware.core.time.NodeClock;
import io.etherware.rt.platform.internal.LinuxClock;
import java.lang.foreign.Arena;
import java.lang.foreign.MemorySegment;
import java.util.Objects;
import java.util.Optional;

/**
 * Sleeps to an absolute time of {@link System#nanoTime()} the way {@code cyclictest} does:
 * {@code clock_nanosleep(CLOCK_MONOTONIC, TIMER_ABSTIME, ...)}, through the FFM API. The kernel
 * wakes the thread at the deadline itself, with no relative time computed before the call (which a
 * preemption between reading the clock and sleeping would make late), and a SCHED_FIFO thread has
 * no timer slack.
 *
 * <p>The sleep cannot be ended early: neither {@link java.util.concurrent.locks.LockSupport#unpark}
 * nor an interrupt reaches a thread inside it. Sleep to deadlines a period away or less, and where
 * another thread must be able to wake the sleeper, park first and sleep here only for the last
 * stretch (the Notifier does). A thread inside the call is in native code, so a safepoint does not
 * wait for it.
 *
 * <p>{@link #forClock} falls back to {@link DeadlineSleeper#parking} where the call is not
 * usable (not Linux, native access denied, a clock that is not the system's); {@link #describe}
 * says which. An instance belongs to the thread that sleeps with it; it allocates nothing per sleep.
 */
public final class AbsoluteSleeper implements DeadlineSleeper {

    private final MemorySegment timespec = Arena.ofAuto().allocate(LinuxClock.TIMESPEC_BYTES, 8);

    private AbsoluteSleeper() {
    }

    /**
     * Whether {@code clock_nanosleep} can be used in this JVM.
     *
     * @return true on Linux with native access allowed, libc's {@code clock_nanosleep} and
     *         {@code clock_gettime} found, and {@code System.nanoTime()} reading CLOCK_MONOTONIC
     */
    public static boolean isAvailable() {
        return LinuxClock.isAvailable();
    }

    /**
     * Why {@code clock_nanosleep} cannot be used.
     *
     * @return the reason, for reports; empty when {@link #isAvailable()}
     */
    public static Optional<String> unavailableReason() {
        return LinuxClock.unavailableReason();
    }

    /**
     * An absolute sleeper on {@code clock}, for one thread (it may be made on another): {@code
     * clock_nanosleep} when {@code clock} is {@link NodeClock#system()} and the call is usable, else
     * {@link DeadlineSleeper#parking}.
     *
     * @param clock the clock whose {@code nanoTime()} the deadlines are on
     * @return the sleeper; use it on one thread only
     * @throws NullPointerException when {@code clock} is null
     */
    public static DeadlineSleeper forClock(NodeClock clock) {
        Objects.requireNonNull(clock, "clock");
        return clock == NodeClock.system() && isAvailable() ? new AbsoluteSleeper() : DeadlineSleeper.parking(clock);
    }

    /**
     * What a sleeper does, for reports.
     *
     * @param sleeper a sleeper, typically from {@link #forClock}
     * @return the kernel call for this class's sleeper; else {@code LockSupport.parkNanos} and why
     *         the kernel call is not used
     */
    public static String describe(DeadlineSleeper sleeper) {
        if (sleeper instanceof AbsoluteSleeper) {
            return "clock_nanosleep(CLOCK_MONOTONIC, TIMER_ABSTIME)";
        }
        return "LockSupport.parkNanos (" + unavailableReason().orElse("not the system clock, or not this class's sleeper")
                + ")";
    }

    /**
     * Sleeps until {@code System.nanoTime()} reaches {@code deadlineNs}; returns at once if it has.
     * Resumes after a signal; neither an interrupt nor {@code unpark} ends it. Allocates nothing.
     * Call it only on the thread this sleeper belongs to.
     *
     * @param deadlineNs the absolute wake-up time on {@link System#nanoTime()}, in nanoseconds
     * @throws IllegalStateException when {@code clock_nanosleep} fails with an error other than EINTR
     */
    @Override
    public void sleepUntil(long deadlineNs) {
        LinuxClock.sleepUntil(deadlineNs, timespec);
    }
}
