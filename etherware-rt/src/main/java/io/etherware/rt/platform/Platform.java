package io.etherware.rt.platform;

import io.etherware.rt.platform.internal.Errno;
import io.etherware.rt.platform.internal.LinuxNative;
import io.etherware.rt.platform.internal.NativeResult;
import io.etherware.rt.platform.internal.RealtimeBudget;
import io.etherware.rt.platform.internal.RefusalAdvice;
import io.etherware.rt.platform.internal.RefusalWarnings;
import java.util.ArrayList;
import java.util.List;
import java.util.Objects;
import java.util.Optional;
import java.util.OptionalLong;

/**
 * The OS's real-time features for the threads of this JVM: scheduling policy and priority, CPU
 * affinity, memory locking, read back from the OS.
 *
 * <p>Refusals never throw: when the OS says no (EPERM without CAP_SYS_NICE or RLIMIT_RTPRIO,
 * EINVAL for a priority out of range) or the platform lacks the call (not Linux, symbol missing),
 * the refusal is logged once per kind at WARN with the errno and the fix, returned to the caller,
 * and the thread runs on with what it has (design decision 6).
 *
 * <p>Thread-safety: thread-safe. The {@code configureCurrentThread} and {@code currentThread…}
 * methods act on the calling thread. Each call makes a few system calls and allocates a little: call
 * it when a thread starts, not per message.
 */
public final class Platform {

    private static final Platform CURRENT = new Platform(RefusalWarnings.shared());

    private final RefusalWarnings warnings;

    Platform(RefusalWarnings warnings) {
        this.warnings = Objects.requireNonNull(warnings, "warnings");
    }

    /**
     * The platform of this JVM.
     *
     * @return the one shared instance, whose refusal warnings are once per JVM
     */
    public static Platform current() {
        return CURRENT;
    }

    /**
     * Whether the OS calls can be made at all.
     *
     * @return true on Linux with the libc symbols found and native access allowed
     */
    public boolean isAvailable() {
        return LinuxNative.isAvailable();
    }

    /**
     * Why the OS calls cannot be made.
     *
     * @return the reason, for reports; empty when {@link #isAvailable()}
     */
    public Optional<String> unavailableReason() {
        return LinuxNative.unavailableReason();
    }

    /**
     * The calling thread's kernel thread id.
     *
     * @return the id {@code ps -L} and {@code chrt -p} show, or -1 when the platform cannot say
     */
    public int currentThreadId() {
        return LinuxNative.currentThreadId();
    }

    /**
     * Asks the OS to run the calling thread at {@code requested} on {@code cpus}, then reads back
     * what it granted.
     *
     * <p>A real-time policy is set with {@code SCHED_RESET_ON_FORK}, so threads this thread
     * creates (a lazily started pool worker, say) start at SCHED_OTHER instead of inheriting a
     * real-time priority nobody asked for. The affinity is set first, so the thread is already
     * where it belongs when it becomes real-time. Under a {@link CpuPartition}, {@link
     * CpuSet#inherit()} means the partition's real-time CPUs for a real-time request and its
     * ordinary CPUs otherwise. Refusals are logged once per kind and returned, never thrown.
     *
     * @param requested the policy and priority to run at
     * @param cpus      the CPUs to run on, or {@link CpuSet#inherit()} to leave the affinity alone
     *                  (outside a partition)
     * @return what was asked and what the OS reports it granted, with the refusals
     */
    public ThreadGrant configureCurrentThread(ThreadPolicy requested, CpuSet cpus) {
        ThreadGrant grant = configureCurrentThreadWithoutWarning(requested, cpus);
        warnOnce(grant.refusals());
        return grant;
    }

    /**
     * {@link #configureCurrentThread}, but leaves the warning to the caller: for code that
     * configures several threads and then warns once for all of them with {@link #warnOnce},
     * most demanding request first, so the fix it quotes is enough for every thread.
     *
     * @param requested the policy and priority to run at
     * @param cpus      the CPUs to run on, or {@link CpuSet#inherit()} to leave the affinity alone
     *                  (outside a partition)
     * @return what was asked and what the OS reports it granted, with the refusals, not yet logged
     */
    public ThreadGrant configureCurrentThreadWithoutWarning(ThreadPolicy requested, CpuSet cpus) {
        Objects.requireNonNull(requested, "requested");
        Objects.requireNonNull(cpus, "cpus");
        var refusals = new ArrayList<PlatformRefusal>();
        CpuPartition.Placed placed = CpuPartition.place(requested, cpus);
        cpus = placed.cpus();
        if (placed.result() != null && !placed.result().ok()) {
            refusals.add(refusal("cpu affinity", cpus.toString(), placed.result().errno(),
                    RefusalAdvice.forAffinity(cpus, placed.result().errno(), LinuxNative.getAffinity(0))));
        }
        if (requested.isRealtime() || LinuxNative.isAvailable()) {
            // The queries that report the grant, once at the inherited priority: their first call
            // links and loads, which at a real-time priority could wait on ordinary threads that
            // the real-time ones starve.
            LinuxNative.currentThreadId();
            currentThreadPolicy();
            currentThreadAffinity();
            int flags = requested.isRealtime() ? LinuxNative.SCHED_RESET_ON_FORK : 0;
            NativeResult result = LinuxNative.setScheduler(0, osPolicy(requested.policy()) | flags,
                    requested.priority());
            if (!result.ok() && result.errno() == Errno.EPERM && requested.isRealtime()
                    && CpuPartition.releaseForRealtime()) {
                // Put in a partition's ordinary cpu group by a partition that opened after place():
                // out of it now, and asked again.
                result = LinuxNative.setScheduler(0, osPolicy(requested.policy()) | flags, requested.priority());
            }
            if (!result.ok()) {
                int osPolicy = osPolicy(requested.policy());
                refusals.add(refusal("thread priority", requested.toString(), result.errno(),
                        RefusalAdvice.forPolicy(requested, result.errno(), LinuxNative.realtimePriorityLimit(),
                                LinuxNative.priorityMin(osPolicy).value(), LinuxNative.priorityMax(osPolicy).value(),
                                result.errno() == Errno.EPERM ? RealtimeBudget.ofCurrentThread()
                                        : RealtimeBudget.UNKNOWN)));
            }
        }
        return new ThreadGrant(Thread.currentThread().getName(), LinuxNative.currentThreadId(), requested,
                currentThreadPolicy(), cpus, currentThreadAffinity(), refusals);
    }

    /**
     * Splits this JVM's CPUs between real-time threads ({@code realtimeCpus}) and every other
     * thread, the JVM's own included, and keeps it so while the partition is open; see {@link
     * CpuPartition}. Call it before the real-time threads start. A JVM has one partition: opening
     * it again with the same CPUs shares it (each holder closes its share), with other CPUs fails.
     * Where the platform cannot set affinities the partition holds nothing, warns once and says
     * why in {@link CpuPartition#refusals()}.
     *
     * @param realtimeCpus the CPUs for the real-time threads; they need not be among the calling
     *                     thread's CPUs
     * @return this caller's share of the partition; close it when the real-time threads are done
     * @throws IllegalArgumentException when {@code realtimeCpus} is inherit, names a CPU that is not
     *                                  online, or leaves none of the caller's CPUs for the other threads
     * @throws IllegalStateException    when another partition, with other CPUs, is open
     */
    public CpuPartition partitionCpus(CpuSet realtimeCpus) {
        return CpuPartition.open(realtimeCpus);
    }

    /**
     * This JVM's CPU partition, if one is open.
     *
     * @return a view of the partition that holds no share (closing it does nothing); empty when
     *         none is open
     */
    public Optional<CpuPartition> cpuPartition() {
        return Optional.ofNullable(CpuPartition.current());
    }

    /**
     * Logs each refusal at WARN with its errno and fix, unless one of its kind (feature and errno)
     * was already logged in this JVM. Of several refusals of one kind only the first given is
     * quoted: give the most demanding first.
     *
     * @param refusals the refusals, most demanding first; may be empty
     */
    public void warnOnce(List<PlatformRefusal> refusals) {
        refusals.forEach(warnings::warnOnce);
    }

    /**
     * The calling thread's policy and priority as the OS reports them.
     *
     * @return the policy; {@link ThreadPolicy#NON_REALTIME} when the platform cannot say, or for a
     *         policy without a static priority (SCHED_BATCH, SCHED_IDLE, SCHED_DEADLINE)
     */
    public ThreadPolicy currentThreadPolicy() {
        return threadPolicy(0).orElse(ThreadPolicy.NON_REALTIME);
    }

    /**
     * Any thread's policy and priority as the OS reports them (0 means the calling thread); empty
     * when it cannot be read (no such thread, platform unavailable). SCHED_BATCH, SCHED_IDLE and
     * SCHED_DEADLINE are reported as {@link ThreadPolicy#NON_REALTIME}: they carry no static
     * priority.
     *
     * @param osThreadId a kernel thread id of this process, as from {@link #currentThreadId()}, or
     *                   0 for the calling thread
     * @return the policy; empty when it cannot be read
     */
    public Optional<ThreadPolicy> threadPolicy(int osThreadId) {
        NativeResult policy = LinuxNative.getScheduler(osThreadId);
        NativeResult priority = LinuxNative.getPriority(osThreadId);
        if (!policy.ok() || !priority.ok()) {
            return Optional.empty();
        }
        return Optional.of(switch (policy.value()) {
            case LinuxNative.SCHED_FIFO -> ThreadPolicy.fifo(priority.value());
            case LinuxNative.SCHED_RR -> ThreadPolicy.roundRobin(priority.value());
            default -> ThreadPolicy.NON_REALTIME;
        });
    }

    /**
     * The CPUs the calling thread may run on, as the OS reports them.
     *
     * @return the CPUs; {@link CpuSet#inherit()} when unknown
     */
    public CpuSet currentThreadAffinity() {
        int[] cpus = LinuxNative.getAffinity(0);
        return cpus == null || cpus.length == 0 ? CpuSet.inherit() : CpuSet.of(cpus);
    }

    /**
     * Locks the process's current and future pages in RAM ({@code mlockall(MCL_CURRENT |
     * MCL_FUTURE)}), so a page fault never stalls a real-time thread. Every page the JVM maps
     * from now on is locked and populated too, thread stacks included, and the JVM maps more than
     * its heap: a {@code -Xmx32m} JDK 25 JVM measured 315 MB resident after this call. Size the
     * JVM for it (fixed heap {@code -Xms} = {@code -Xmx}, {@code -XX:+AlwaysPreTouch}, a bounded
     * {@code -XX:ReservedCodeCacheSize}) and call it once, at start.
     *
     * @return empty when locked, else the refusal (also logged once)
     */
    public Optional<PlatformRefusal> lockMemory() {
        NativeResult result = LinuxNative.lockAll(LinuxNative.MCL_CURRENT | LinuxNative.MCL_FUTURE);
        if (result.ok()) {
            return Optional.empty();
        }
        PlatformRefusal refusal = refusal("memory lock", "mlockall(MCL_CURRENT|MCL_FUTURE)", result.errno(),
                RefusalAdvice.forMemoryLock(result.errno()));
        warnings.warnOnce(refusal);
        return Optional.of(refusal);
    }

    /**
     * The soft RLIMIT_RTPRIO: the highest real-time priority an unprivileged thread may take
     * ({@link Long#MAX_VALUE} for unlimited); empty when unknown. Root and CAP_SYS_NICE are not
     * bound by it.
     *
     * @return the soft limit, {@link Long#MAX_VALUE} for unlimited; empty when unknown
     */
    public OptionalLong realtimePriorityLimit() {
        long[] limit = LinuxNative.realtimePriorityLimit();
        if (limit == null) {
            return OptionalLong.empty();
        }
        return OptionalLong.of(limit[0] == LinuxNative.RLIM_INFINITY ? Long.MAX_VALUE : limit[0]);
    }

    private static PlatformRefusal refusal(String feature, String requested, int errno, String fix) {
        return new PlatformRefusal(feature, requested, errno, Errno.name(errno), fix);
    }

    private static int osPolicy(SchedulingPolicy policy) {
        return switch (policy) {
            case OTHER -> LinuxNative.SCHED_OTHER;
            case FIFO -> LinuxNative.SCHED_FIFO;
            case RR -> LinuxNative.SCHED_RR;
        };
    }

    /** For tests: the warning sink of this instance. */
    RefusalWarnings warnings() {
        return warnings;
    }
}
