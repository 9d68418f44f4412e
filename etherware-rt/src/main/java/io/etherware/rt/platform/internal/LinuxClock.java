package io.etherware.rt.platform.internal;

import static java.lang.foreign.ValueLayout.ADDRESS;
import static java.lang.foreign.ValueLayout.JAVA_INT;
import static java.lang.foreign.ValueLayout.JAVA_LONG;

import java.lang.foreign.Arena;
import java.lang.foreign.FunctionDescriptor;
import java.lang.foreign.Linker;
import java.lang.foreign.MemorySegment;
import java.lang.foreign.SymbolLookup;
import java.lang.invoke.MethodHandle;
import java.util.Optional;

/**
 * {@code clock_nanosleep(CLOCK_MONOTONIC, TIMER_ABSTIME, ...)} and {@code clock_gettime}, through the
 * FFM API: an absolute sleep on the clock behind {@link System#nanoTime()}.
 *
 * <p>Usable only when libc has both calls and {@code System.nanoTime()} reads CLOCK_MONOTONIC (it
 * does on Linux HotSpot; checked once here, since the JDK does not promise it). The sleep call is
 * an ordinary downcall, not a critical one: a thread inside it is in native code, which a safepoint
 * does not wait for.
 *
 * <p>Thread-safety: thread-safe; {@link #sleepUntil} writes only the segment it is given, which its
 * caller owns.
 */
@SuppressWarnings("restricted") // linking native functions is this class's purpose
public final class LinuxClock {

    /** Bytes of a {@code struct timespec} on 64-bit Linux. */
    public static final long TIMESPEC_BYTES = 16;

    private static final int CLOCK_MONOTONIC = 1;
    private static final int TIMER_ABSTIME = 1;
    private static final long NANOS_PER_SECOND = 1_000_000_000L;
    /** How far {@code System.nanoTime()} may sit from CLOCK_MONOTONIC and still be taken as it. */
    private static final long SAME_CLOCK_TOLERANCE_NS = 1_000_000L;

    private static final MethodHandle CLOCK_NANOSLEEP;
    private static final String UNAVAILABLE_REASON;

    static {
        MethodHandle sleep = null;
        String reason = LinuxNative.unavailableReason().orElse(null);
        if (reason == null) {
            try {
                Linker linker = Linker.nativeLinker();
                SymbolLookup libc = linker.defaultLookup();
                sleep = libc.find("clock_nanosleep").map(address -> linker.downcallHandle(address,
                        FunctionDescriptor.of(JAVA_INT, JAVA_INT, JAVA_INT, ADDRESS, ADDRESS))).orElse(null);
                MethodHandle getTime = libc.find("clock_gettime").map(address -> linker.downcallHandle(address,
                        FunctionDescriptor.of(JAVA_INT, JAVA_INT, ADDRESS))).orElse(null);
                if (sleep == null || getTime == null) {
                    reason = "libc has no clock_nanosleep/clock_gettime";
                } else {
                    reason = sameClockOrReason(getTime);
                }
            } catch (RuntimeException | LinkageError e) {
                reason = "the Foreign Function API is not usable here: " + e;
            }
        }
        UNAVAILABLE_REASON = reason;
        CLOCK_NANOSLEEP = reason == null ? sleep : null;
    }

    private LinuxClock() {
    }

    /** Whether {@link #sleepUntil} can be used. */
    public static boolean isAvailable() {
        return UNAVAILABLE_REASON == null;
    }

    /** Why {@link #sleepUntil} cannot be used; empty when it can. */
    public static Optional<String> unavailableReason() {
        return Optional.ofNullable(UNAVAILABLE_REASON);
    }

    /**
     * Sleeps the calling thread until {@code System.nanoTime()} reaches {@code deadlineNs}, resuming
     * after a signal. Returns at once for a deadline already past.
     *
     * @param timespec a {@link #TIMESPEC_BYTES}-byte segment, 8-aligned, owned by the caller
     * @throws IllegalStateException when unavailable, or the call fails for another reason than EINTR
     */
    public static void sleepUntil(long deadlineNs, MemorySegment timespec) {
        if (CLOCK_NANOSLEEP == null) {
            throw new IllegalStateException("clock_nanosleep is not usable: " + UNAVAILABLE_REASON);
        }
        // System.nanoTime() is CLOCK_MONOTONIC here (checked at class load), so its value is the
        // absolute time to sleep to; a negative one (an origin near boot) is in the past anyway.
        long deadline = Math.max(0, deadlineNs);
        timespec.set(JAVA_LONG, 0, deadline / NANOS_PER_SECOND);
        timespec.set(JAVA_LONG, 8, deadline % NANOS_PER_SECOND);
        int rc;
        do {
            try {
                // Returns the error number itself (not -1 and errno), 0 at the deadline.
                rc = (int) CLOCK_NANOSLEEP.invokeExact(CLOCK_MONOTONIC, TIMER_ABSTIME, timespec,
                        MemorySegment.NULL);
            } catch (Throwable t) {
                throw new IllegalStateException("clock_nanosleep failed to run", t);
            }
        } while (rc == Errno.EINTR);
        if (rc != 0) {
            throw new IllegalStateException("clock_nanosleep(CLOCK_MONOTONIC, TIMER_ABSTIME, "
                    + deadline + " ns) failed: " + Errno.name(rc) + " (" + rc + ")");
        }
    }

    private static String sameClockOrReason(MethodHandle getTime) {
        try (Arena arena = Arena.ofConfined()) {
            MemorySegment timespec = arena.allocate(TIMESPEC_BYTES, 8);
            long bestGapNs = Long.MAX_VALUE;
            long offsetNs = 0;
            for (int attempt = 0; attempt < 5; attempt++) {
                long beforeNs = System.nanoTime();
                int rc = (int) getTime.invokeExact(CLOCK_MONOTONIC, timespec);
                long afterNs = System.nanoTime();
                if (rc != 0) {
                    return "clock_gettime(CLOCK_MONOTONIC) failed";
                }
                long monotonicNs = timespec.get(JAVA_LONG, 0) * NANOS_PER_SECOND + timespec.get(JAVA_LONG, 8);
                if (afterNs - beforeNs < bestGapNs) {
                    bestGapNs = afterNs - beforeNs;
                    offsetNs = monotonicNs - (beforeNs + (afterNs - beforeNs) / 2);
                }
            }
            return Math.abs(offsetNs) <= SAME_CLOCK_TOLERANCE_NS ? null
                    : "System.nanoTime() is not CLOCK_MONOTONIC in this JVM (" + offsetNs + " ns apart)";
        } catch (Throwable t) {
            return "clock_gettime failed to run: " + t;
        }
    }
}
