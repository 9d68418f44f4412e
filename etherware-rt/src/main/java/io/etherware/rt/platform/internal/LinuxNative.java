package io.etherware.rt.platform.internal;

import static java.lang.foreign.ValueLayout.ADDRESS;
import static java.lang.foreign.ValueLayout.JAVA_INT;
import static java.lang.foreign.ValueLayout.JAVA_LONG;

import java.lang.foreign.Arena;
import java.lang.foreign.FunctionDescriptor;
import java.lang.foreign.Linker;
import java.lang.foreign.MemoryLayout;
import java.lang.foreign.MemorySegment;
import java.lang.foreign.StructLayout;
import java.lang.foreign.SymbolLookup;
import java.lang.invoke.MethodHandle;
import java.lang.invoke.VarHandle;
import java.util.Locale;
import java.util.Optional;

/**
 * The libc scheduling calls, through the Foreign Function &amp; Memory API (no JNI): policy and
 * priority of a thread, memory locking, CPU affinity, RLIMIT_RTPRIO, and the kernel thread id.
 *
 * <p>Every call that can fail captures {@code errno} with {@code Linker.Option.captureCallState}
 * right after the call, before the JVM can overwrite it. On a platform that is not Linux, or when a
 * symbol is missing, the calls return {@link NativeResult#UNAVAILABLE} instead of throwing, and
 * {@link #unavailableReason()} says why.
 *
 * <p>Thread-safety: all methods are thread-safe and allocate only a small confined arena per
 * call; none is meant for a per-message path. Thread id {@code 0} means the calling thread: on
 * Linux {@code sched_setscheduler(0, ...)} applies to the calling thread, not the whole process.
 */
@SuppressWarnings("restricted") // linking native functions is this class's purpose
public final class LinuxNative {

    public static final int SCHED_OTHER = 0;
    public static final int SCHED_FIFO = 1;
    public static final int SCHED_RR = 2;
    /** Threads created by a thread with this flag start at SCHED_OTHER instead of inheriting. */
    public static final int SCHED_RESET_ON_FORK = 0x40000000;
    public static final int MCL_CURRENT = 1;
    public static final int MCL_FUTURE = 2;
    /** {@code rlim_t} value for "no limit". */
    public static final long RLIM_INFINITY = -1L;
    /** Bits in glibc's {@code cpu_set_t}. */
    public static final int CPU_SETSIZE = 1024;

    private static final int RLIMIT_RTPRIO = 14;
    private static final long CPU_SET_BYTES = CPU_SETSIZE / 8;

    private static final String UNAVAILABLE_REASON;
    private static final StructLayout CAPTURE_LAYOUT;
    private static final VarHandle ERRNO;
    private static final MethodHandle SCHED_SETSCHEDULER;
    private static final MethodHandle SCHED_GETSCHEDULER;
    private static final MethodHandle SCHED_GETPARAM;
    private static final MethodHandle SCHED_GET_PRIORITY_MIN;
    private static final MethodHandle SCHED_GET_PRIORITY_MAX;
    private static final MethodHandle SCHED_SETAFFINITY;
    private static final MethodHandle SCHED_GETAFFINITY;
    private static final MethodHandle MLOCKALL;
    private static final MethodHandle GETRLIMIT;
    private static final MethodHandle GETTID;

    static {
        String reason = null;
        StructLayout captureLayout = null;
        VarHandle errno = null;
        MethodHandle setScheduler = null;
        MethodHandle getScheduler = null;
        MethodHandle getParam = null;
        MethodHandle priorityMin = null;
        MethodHandle priorityMax = null;
        MethodHandle setAffinity = null;
        MethodHandle getAffinity = null;
        MethodHandle mlockall = null;
        MethodHandle getrlimit = null;
        MethodHandle gettid = null;
        String osName = System.getProperty("os.name", "unknown");
        if (!osName.toLowerCase(Locale.ROOT).startsWith("linux")) {
            reason = "os.name=" + osName + " is not Linux";
        } else {
            try {
                Linker linker = Linker.nativeLinker();
                SymbolLookup libc = linker.defaultLookup();
                Linker.Option errnoOption = Linker.Option.captureCallState("errno");
                captureLayout = Linker.Option.captureStateLayout();
                errno = captureLayout.varHandle(MemoryLayout.PathElement.groupElement("errno"));
                setScheduler = find(linker, libc, "sched_setscheduler",
                        FunctionDescriptor.of(JAVA_INT, JAVA_INT, JAVA_INT, ADDRESS), errnoOption);
                getScheduler = find(linker, libc, "sched_getscheduler",
                        FunctionDescriptor.of(JAVA_INT, JAVA_INT), errnoOption);
                getParam = find(linker, libc, "sched_getparam",
                        FunctionDescriptor.of(JAVA_INT, JAVA_INT, ADDRESS), errnoOption);
                priorityMin = find(linker, libc, "sched_get_priority_min",
                        FunctionDescriptor.of(JAVA_INT, JAVA_INT), errnoOption);
                priorityMax = find(linker, libc, "sched_get_priority_max",
                        FunctionDescriptor.of(JAVA_INT, JAVA_INT), errnoOption);
                setAffinity = find(linker, libc, "sched_setaffinity",
                        FunctionDescriptor.of(JAVA_INT, JAVA_INT, JAVA_LONG, ADDRESS), errnoOption);
                getAffinity = find(linker, libc, "sched_getaffinity",
                        FunctionDescriptor.of(JAVA_INT, JAVA_INT, JAVA_LONG, ADDRESS), errnoOption);
                mlockall = find(linker, libc, "mlockall", FunctionDescriptor.of(JAVA_INT, JAVA_INT), errnoOption);
                getrlimit = find(linker, libc, "getrlimit",
                        FunctionDescriptor.of(JAVA_INT, JAVA_INT, ADDRESS), errnoOption);
                gettid = libc.find("gettid").map(address -> linker.downcallHandle(address,
                        FunctionDescriptor.of(JAVA_INT))).orElse(null);
                if (setScheduler == null || getScheduler == null || getParam == null) {
                    reason = "libc has no sched_setscheduler/sched_getscheduler/sched_getparam";
                }
            } catch (RuntimeException | LinkageError e) {
                // IllegalCallerException when native access is denied (--illegal-native-access=deny
                // without --enable-native-access), UnsupportedOperationException without a native linker.
                reason = "the Foreign Function API is not usable here: " + e;
            }
        }
        UNAVAILABLE_REASON = reason;
        CAPTURE_LAYOUT = captureLayout;
        ERRNO = errno;
        boolean usable = reason == null;
        SCHED_SETSCHEDULER = usable ? setScheduler : null;
        SCHED_GETSCHEDULER = usable ? getScheduler : null;
        SCHED_GETPARAM = usable ? getParam : null;
        SCHED_GET_PRIORITY_MIN = usable ? priorityMin : null;
        SCHED_GET_PRIORITY_MAX = usable ? priorityMax : null;
        SCHED_SETAFFINITY = usable ? setAffinity : null;
        SCHED_GETAFFINITY = usable ? getAffinity : null;
        MLOCKALL = usable ? mlockall : null;
        GETRLIMIT = usable ? getrlimit : null;
        GETTID = usable ? gettid : null;
    }

    private LinuxNative() {
    }

    private static MethodHandle find(Linker linker, SymbolLookup libc, String name, FunctionDescriptor descriptor,
                                     Linker.Option option) {
        return libc.find(name).map(address -> linker.downcallHandle(address, descriptor, option)).orElse(null);
    }

    /** Whether the thread scheduling calls can be made at all. */
    public static boolean isAvailable() {
        return UNAVAILABLE_REASON == null;
    }

    /** Why the calls cannot be made, or empty when they can. */
    public static Optional<String> unavailableReason() {
        return Optional.ofNullable(UNAVAILABLE_REASON);
    }

    /**
     * The calling thread's kernel thread id, or -1 when unknown. Without libc's {@code gettid}
     * (glibc before 2.30) it is read from the {@code /proc/thread-self} link instead.
     */
    public static int currentThreadId() {
        if (GETTID == null) {
            if (UNAVAILABLE_REASON != null) {
                return -1;
            }
            try {
                // /proc/thread-self -> <pid>/task/<tid>
                java.nio.file.Path link = java.nio.file.Files.readSymbolicLink(java.nio.file.Path.of("/proc/thread-self"));
                return Integer.parseInt(link.getFileName().toString());
            } catch (java.io.IOException | RuntimeException e) {
                return -1;
            }
        }
        try {
            return (int) GETTID.invokeExact();
        } catch (Throwable t) {
            throw new IllegalStateException("gettid failed", t);
        }
    }

    /**
     * {@code sched_setscheduler(tid, policy, {priority})}.
     *
     * @param tid    kernel thread id, 0 for the calling thread
     * @param policy {@link #SCHED_OTHER}, {@link #SCHED_FIFO}, {@link #SCHED_RR}, optionally or-ed
     *               with {@link #SCHED_RESET_ON_FORK}
     */
    public static NativeResult setScheduler(int tid, int policy, int priority) {
        if (SCHED_SETSCHEDULER == null) {
            return NativeResult.UNAVAILABLE;
        }
        try (Arena arena = Arena.ofConfined()) {
            MemorySegment state = arena.allocate(CAPTURE_LAYOUT);
            MemorySegment param = arena.allocate(JAVA_INT);
            param.set(JAVA_INT, 0, priority);
            int rc = (int) SCHED_SETSCHEDULER.invokeExact(state, tid, policy, param);
            return result(rc, state);
        } catch (Throwable t) {
            throw new IllegalStateException("sched_setscheduler failed to link or run", t);
        }
    }

    /** {@code sched_getscheduler(tid)}: the policy, without {@link #SCHED_RESET_ON_FORK}. */
    public static NativeResult getScheduler(int tid) {
        if (SCHED_GETSCHEDULER == null) {
            return NativeResult.UNAVAILABLE;
        }
        try (Arena arena = Arena.ofConfined()) {
            MemorySegment state = arena.allocate(CAPTURE_LAYOUT);
            int rc = (int) SCHED_GETSCHEDULER.invokeExact(state, tid);
            return rc < 0 ? result(rc, state) : new NativeResult(rc & ~SCHED_RESET_ON_FORK, 0);
        } catch (Throwable t) {
            throw new IllegalStateException("sched_getscheduler failed to link or run", t);
        }
    }

    /** {@code sched_getparam(tid)}: the static (real-time) priority, 0 for SCHED_OTHER. */
    public static NativeResult getPriority(int tid) {
        if (SCHED_GETPARAM == null) {
            return NativeResult.UNAVAILABLE;
        }
        try (Arena arena = Arena.ofConfined()) {
            MemorySegment state = arena.allocate(CAPTURE_LAYOUT);
            MemorySegment param = arena.allocate(JAVA_INT);
            int rc = (int) SCHED_GETPARAM.invokeExact(state, tid, param);
            return rc < 0 ? result(rc, state) : new NativeResult(param.get(JAVA_INT, 0), 0);
        } catch (Throwable t) {
            throw new IllegalStateException("sched_getparam failed to link or run", t);
        }
    }

    /** {@code sched_get_priority_min(policy)}. */
    public static NativeResult priorityMin(int policy) {
        return intCall(SCHED_GET_PRIORITY_MIN, policy, "sched_get_priority_min");
    }

    /** {@code sched_get_priority_max(policy)}. */
    public static NativeResult priorityMax(int policy) {
        return intCall(SCHED_GET_PRIORITY_MAX, policy, "sched_get_priority_max");
    }

    /** {@code mlockall(flags)}. */
    public static NativeResult lockAll(int flags) {
        return intCall(MLOCKALL, flags, "mlockall");
    }

    /**
     * {@code sched_setaffinity(tid, sizeof(cpu_set_t), mask)}.
     *
     * @param cpus CPU indexes, each in [0, {@link #CPU_SETSIZE})
     */
    public static NativeResult setAffinity(int tid, int[] cpus) {
        if (SCHED_SETAFFINITY == null) {
            return NativeResult.UNAVAILABLE;
        }
        try (Arena arena = Arena.ofConfined()) {
            MemorySegment state = arena.allocate(CAPTURE_LAYOUT);
            MemorySegment mask = arena.allocate(CPU_SET_BYTES, 8);
            for (int cpu : cpus) {
                long offset = (cpu / 64) * 8L;
                mask.set(JAVA_LONG, offset, mask.get(JAVA_LONG, offset) | (1L << (cpu % 64)));
            }
            int rc = (int) SCHED_SETAFFINITY.invokeExact(state, tid, CPU_SET_BYTES, mask);
            return result(rc, state);
        } catch (Throwable t) {
            throw new IllegalStateException("sched_setaffinity failed to link or run", t);
        }
    }

    /** {@code sched_getaffinity(tid)}: the allowed CPUs, or null when the call failed. */
    public static int[] getAffinity(int tid) {
        if (SCHED_GETAFFINITY == null) {
            return null;
        }
        try (Arena arena = Arena.ofConfined()) {
            MemorySegment state = arena.allocate(CAPTURE_LAYOUT);
            MemorySegment mask = arena.allocate(CPU_SET_BYTES, 8);
            int rc = (int) SCHED_GETAFFINITY.invokeExact(state, tid, CPU_SET_BYTES, mask);
            if (rc < 0) {
                return null;
            }
            int[] cpus = new int[CPU_SETSIZE];
            int count = 0;
            for (int cpu = 0; cpu < CPU_SETSIZE; cpu++) {
                if ((mask.get(JAVA_LONG, (cpu / 64) * 8L) & (1L << (cpu % 64))) != 0) {
                    cpus[count++] = cpu;
                }
            }
            return java.util.Arrays.copyOf(cpus, count);
        } catch (Throwable t) {
            throw new IllegalStateException("sched_getaffinity failed to link or run", t);
        }
    }

    /**
     * RLIMIT_RTPRIO as {soft, hard}; {@link #RLIM_INFINITY} for unlimited. Null when it cannot be
     * read.
     */
    public static long[] realtimePriorityLimit() {
        if (GETRLIMIT == null) {
            return null;
        }
        try (Arena arena = Arena.ofConfined()) {
            MemorySegment state = arena.allocate(CAPTURE_LAYOUT);
            MemorySegment limit = arena.allocate(16, 8);
            int rc = (int) GETRLIMIT.invokeExact(state, RLIMIT_RTPRIO, limit);
            return rc < 0 ? null : new long[] {limit.get(JAVA_LONG, 0), limit.get(JAVA_LONG, 8)};
        } catch (Throwable t) {
            throw new IllegalStateException("getrlimit failed to link or run", t);
        }
    }

    private static NativeResult intCall(MethodHandle handle, int argument, String name) {
        if (handle == null) {
            return NativeResult.UNAVAILABLE;
        }
        try (Arena arena = Arena.ofConfined()) {
            MemorySegment state = arena.allocate(CAPTURE_LAYOUT);
            int rc = (int) handle.invokeExact(state, argument);
            return result(rc, state);
        } catch (Throwable t) {
            throw new IllegalStateException(name + " failed to link or run", t);
        }
    }

    private static NativeResult result(int rc, MemorySegment state) {
        return rc < 0 ? new NativeResult(rc, (int) ERRNO.get(state, 0L)) : new NativeResult(rc, 0);
    }
}
