package io.etherware.rt.platform.internal;

import io.etherware.rt.platform.CpuSet;
import io.etherware.rt.platform.ThreadPolicy;

/**
 * The "how to fix it" sentence of each refusal. Pure functions of what was asked and what the OS
 * said, so they are unit-testable without provoking the refusal. Stateless and thread-safe.
 */
public final class RefusalAdvice {

    private RefusalAdvice() {
    }

    /**
     * Advice for a refused {@code sched_setscheduler}.
     *
     * @param rtprioLimit RLIMIT_RTPRIO {soft, hard}, or null when unknown
     * @param minPriority the policy's minimum priority, or -1 when unknown
     * @param maxPriority the policy's maximum priority, or -1 when unknown
     */
    public static String forPolicy(ThreadPolicy requested, int errno, long[] rtprioLimit, int minPriority,
                                   int maxPriority) {
        return forPolicy(requested, errno, rtprioLimit, minPriority, maxPriority, RealtimeBudget.UNKNOWN);
    }

    /**
     * Advice for a refused {@code sched_setscheduler}, knowing the thread's privilege and cgroup.
     * A privileged thread (CAP_SYS_NICE, as root) refused with EPERM is refused by its cgroup's
     * real-time budget, not by a limit: telling it to run as root would be wrong.
     *
     * @param budget what {@link RealtimeBudget#ofCurrentThread()} read for the refused thread
     * @see #forPolicy(ThreadPolicy, int, long[], int, int)
     */
    public static String forPolicy(ThreadPolicy requested, int errno, long[] rtprioLimit, int minPriority,
                                   int maxPriority, RealtimeBudget budget) {
        if (errno == Errno.EPERM && budget.emptyCpuGroup().isPresent()) {
            String group = budget.emptyCpuGroup().get();
            return "the thread's cpu cgroup '" + group + "' has no real-time budget (cpu.rt_runtime_us=0) and no"
                    + " privilege lifts that; start the JVM in a cgroup with one (e.g. the root: echo $$ >"
                    + " /sys/fs/cgroup/cpu/cgroup.procs before exec) or give '" + group + "' cpu.rt_runtime_us > 0";
        }
        if (errno == Errno.EPERM && budget.capSysNice().orElse(false)) {
            return "the thread holds CAP_SYS_NICE, so no limit refused it: look at its cgroup's real-time budget"
                    + " (cpu.rt_runtime_us, on a kernel with RT group scheduling) or a seccomp or security policy of"
                    + " the container";
        }
        return switch (errno) {
            case Errno.EPERM -> {
                String java = System.getProperty("java.home", "$JAVA_HOME") + "/bin/java";
                String limit = rtprioLimit == null ? "unknown" : "soft=" + limitText(rtprioLimit[0])
                        + ", hard=" + limitText(rtprioLimit[1]);
                boolean limitAllows = rtprioLimit != null
                        && (rtprioLimit[0] == LinuxNative.RLIM_INFINITY || rtprioLimit[0] >= requested.priority());
                String cause = limitAllows
                        ? "RLIMIT_RTPRIO (" + limit + ") allows it, so the process probably lacks CAP_SYS_NICE in a"
                                + " container or its cgroup has no real-time budget (cgroup v1 cpu.rt_runtime_us=0); "
                        : "";
                yield cause + "run as root, or setcap cap_sys_nice+ep " + java
                        + " (containers: --cap-add=SYS_NICE), or raise RLIMIT_RTPRIO (now " + limit + ") to at least "
                        + requested.priority() + ", e.g. '@realtime - rtprio 99' in /etc/security/limits.conf";
            }
            case Errno.EINVAL -> "priority " + requested.priority() + " is outside " + requested.policy().osName()
                    + "'s range" + (minPriority >= 0 ? " [" + minPriority + ", " + maxPriority + "]" : "")
                    + " on this kernel; configure a priority inside it";
            case Errno.ENOSYS -> "real-time scheduling is not available here ("
                    + LinuxNative.unavailableReason().orElse("sched_setscheduler missing")
                    + "); run on Linux with --enable-native-access for io.etherware.rt (or ALL-UNNAMED)";
            default -> "see sched_setscheduler(2) for " + Errno.name(errno);
        };
    }

    /** Advice for a refused {@code sched_setaffinity}. */
    public static String forAffinity(CpuSet requested, int errno, int[] allowedCpus) {
        return switch (errno) {
            case Errno.EINVAL -> "CPU set " + requested + " contains no CPU that is online and allowed for this"
                    + " process" + (allowedCpus != null ? " (allowed: " + cpuText(allowedCpus) + ")" : "")
                    + "; pick CPUs from the allowed set (taskset -cp, cpuset cgroup)";
            case Errno.EPERM -> "the process may not change this thread's affinity; run as root or grant CAP_SYS_NICE";
            case Errno.ENOSYS -> "CPU affinity is not available here ("
                    + LinuxNative.unavailableReason().orElse("sched_setaffinity missing") + ")";
            default -> "see sched_setaffinity(2) for " + Errno.name(errno);
        };
    }

    /** Advice for a refused {@code mlockall}. */
    public static String forMemoryLock(int errno) {
        return switch (errno) {
            case Errno.ENOMEM, Errno.EPERM, Errno.EAGAIN -> "raise RLIMIT_MEMLOCK (ulimit -l unlimited, or"
                    + " '@realtime - memlock unlimited' in /etc/security/limits.conf), or grant CAP_IPC_LOCK"
                    + " (setcap cap_ipc_lock+ep on java), or run as root";
            case Errno.ENOSYS -> "memory locking is not available here ("
                    + LinuxNative.unavailableReason().orElse("mlockall missing") + ")";
            default -> "see mlockall(2) for " + Errno.name(errno);
        };
    }

    private static String limitText(long value) {
        return value == LinuxNative.RLIM_INFINITY ? "unlimited" : Long.toString(value);
    }

    private static String cpuText(int[] cpus) {
        return cpus.length == 0 ? "none" : CpuSet.of(cpus).toString();
    }
}
