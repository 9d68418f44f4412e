package io.etherware.rt.platform;

import io.etherware.rt.platform.internal.Errno;
import io.etherware.rt.platform.internal.LinuxNative;
import io.etherware.rt.platform.internal.NativeResult;
import io.etherware.rt.platform.internal.OrdinaryCpuGroup;
import io.etherware.rt.platform.internal.RefusalAdvice;
import java.io.IOException;
import java.nio.file.Files;
import java.nio.file.Path;
import java.util.ArrayList;
import java.util.Arrays;
import java.util.List;
import java.util.Map;
import java.util.Objects;
import java.util.HashMap;
import java.util.HashSet;
import java.util.Set;
import java.util.concurrent.atomic.AtomicBoolean;
import java.util.concurrent.atomic.AtomicLong;
import java.util.concurrent.locks.LockSupport;
import java.util.stream.IntStream;
import org.slf4j.Logger;
import org.slf4j.LoggerFactory;

/**
 * The JVM's CPUs split in two: the real-time CPUs, for the threads that run at a real-time policy
 * (dispatchers, Notifier, network threads, a plant's board), and the ordinary CPUs, for every other
 * thread of the JVM, its own included (JIT compilers, collector threads, ordinary Java threads).
 *
 * <p>Why: a HotSpot safepoint (every G1 collection, deoptimization, many JVM operations) waits
 * until every Java thread has stopped, and an ordinary thread that a real-time thread keeps off its
 * CPU reaches the safepoint only when it runs again, which under a stress task can be tens of
 * milliseconds while every real-time thread stands still. With the ordinary threads on other CPUs,
 * nothing runnable waits behind a real-time thread.
 *
 * <p>What it does, from {@link Platform#partitionCpus}: moves every thread of the process to the
 * ordinary CPUs (the opening thread's CPUs without the real-time ones); from then on {@link
 * Platform#configureCurrentThread} gives a thread that asks for {@link CpuSet#inherit()} the
 * real-time CPUs when it asks for a real-time policy and the ordinary CPUs otherwise; and a keeper
 * thread (ordinary, on the ordinary CPUs) looks once a second for ordinary threads that landed on a
 * real-time CPU and moves them back. They land there because Linux gives a new thread its
 * creator's affinity: a pool thread started lazily from a dispatcher, say. {@link
 * #threadsMovedBack()} counts them. A thread the platform placed on a real-time CPU itself (a
 * real-time request, or an explicit request for those CPUs) is left alone, even where its real-time
 * policy was refused.
 *
 * <p>Where it can (a cgroup v1 {@code cpu} hierarchy whose files the process may write, as root),
 * the partition also puts the JVM's ordinary threads in a cpu cgroup of its own ({@link
 * #ordinaryCpuGroup()}), so that a safepoint rarely waits while the kernel runs another JVM's
 * threads on the ordinary CPUs. The threads the platform configures stay out of it, and one born in
 * it is moved out when the platform configures it: a new group has no real-time budget. A thread
 * that sets a real-time policy without the platform (JNI, {@code chrt -p}), or a non-Java process
 * started from an ordinary thread, is refused in the group.
 *
 * <p>The real-time CPUs need not be among the opening thread's CPUs: a JVM started by a partitioned
 * one inherits only the ordinary CPUs, and still puts its real-time threads on the real-time ones.
 *
 * <p>One partition per JVM: {@link Platform#partitionCpus} with the same CPUs again gives another
 * holder of it, with other CPUs fails. Each holder closes once (a second close of the same holder
 * does nothing); when the last has closed, the keeper stops and the threads the partition moved go
 * back to the CPUs they had (a thread that came to the real-time CPUs by inheritance, or started
 * during the partition, to the opener's CPUs and the real-time ones). Where the platform cannot
 * set or read affinities, the partition holds nothing and says why in {@link #refusals()}.
 *
 * <p>Thread-safe: opening, closing, each sweep of the keeper and each thread's placement by the
 * platform take one lock, so none of them sees another half done. A sweep makes a few system calls
 * per thread of the JVM, once a second. Thread ids are the kernel's; one that ends and is reused by
 * a new thread within a second of a sweep may be taken for the old one.
 */
public final class CpuPartition implements AutoCloseable {

    private static final Logger LOG = LoggerFactory.getLogger(CpuPartition.class);
    /** How often the keeper looks for ordinary threads on the real-time CPUs. */
    static final long KEEPER_PERIOD_NS = 1_000_000_000L;

    /** Guards {@link #current} and everything every {@link Shared} does to thread affinities. */
    private static final Object LOCK = new Object();
    private static Shared current;
    /**
     * Kernel thread ids the platform configured, in this JVM, partition or not: never put in the
     * ordinary cpu group (they may run, or be lent, a real-time policy, which it cannot grant).
     */
    private static final Set<Integer> CONFIGURED = new HashSet<>();
    /** Above this many, {@link #CONFIGURED} forgets the threads that ended. */
    private static final int CONFIGURED_PRUNE_AT = 1024;

    private final Shared shared;
    private final AtomicBoolean closed;

    private CpuPartition(Shared shared, boolean owner) {
        this.shared = shared;
        this.closed = new AtomicBoolean(!owner);
    }

    /** Opens the partition, or joins the JVM's one when it has the same real-time CPUs. */
    static CpuPartition open(CpuSet realtimeCpus) {
        Objects.requireNonNull(realtimeCpus, "realtimeCpus");
        if (realtimeCpus.isInherit()) {
            throw new IllegalArgumentException("realtimeCpus=inherit: name the real-time CPUs, e.g. CpuSet.of(1)");
        }
        synchronized (LOCK) {
            if (current != null) {
                if (!current.realtimeCpus.equals(realtimeCpus)) {
                    throw new IllegalStateException("realtimeCpus=" + realtimeCpus + ": this JVM's CPUs are already"
                            + " partitioned with real-time CPUs " + current.realtimeCpus
                            + "; give every node of one JVM the same real-time CPUs");
                }
                current.holders++;
                return new CpuPartition(current, true);
            }
            int[] allowed = LinuxNative.isAvailable() ? LinuxNative.getAffinity(0) : null;
            if (allowed == null || allowed.length == 0) {
                PlatformRefusal refusal = new PlatformRefusal("cpu partition", realtimeCpus.toString(), Errno.ENOSYS,
                        Errno.name(Errno.ENOSYS), "CPU affinity needs Linux with native access ("
                        + LinuxNative.unavailableReason().orElse("sched_getaffinity failed")
                        + "); the threads run on every CPU");
                Platform.current().warnOnce(List.of(refusal));
                return new CpuPartition(Shared.inert(realtimeCpus, refusal), true);
            }
            int[] online = onlineCpus();
            for (int cpu : realtimeCpus.cpus()) {
                if (online != null && Arrays.stream(online).noneMatch(onlineCpu -> onlineCpu == cpu)) {
                    throw new IllegalArgumentException("realtimeCpus=" + realtimeCpus + ": CPU " + cpu
                            + " is not online (online: " + CpuSet.of(online) + ")");
                }
            }
            int[] ordinary = Arrays.stream(allowed).filter(cpu -> !realtimeCpus.contains(cpu)).toArray();
            if (ordinary.length == 0) {
                throw new IllegalArgumentException("realtimeCpus=" + realtimeCpus + " leaves no CPU of "
                        + CpuSet.of(allowed) + " for the JVM's other threads; keep at least one out of it");
            }
            int[] all = IntStream.concat(Arrays.stream(allowed), Arrays.stream(realtimeCpus.cpus())).distinct()
                    .sorted().toArray();
            current = new Shared(realtimeCpus, CpuSet.of(ordinary), CpuSet.of(all));
            LOG.info("{}", current.describe());
            if (!current.refusals.isEmpty()) {
                Platform.current().warnOnce(List.of(current.refusals.get(0)));
            }
            return new CpuPartition(current, true);
        }
    }

    /** A view of the JVM's partition that holds nothing (its close does nothing), or null. */
    static CpuPartition current() {
        synchronized (LOCK) {
            return current == null ? null : new CpuPartition(current, false);
        }
    }

    /**
     * Sets the calling thread's CPUs for a request of {@code requested} on {@code cpus}, under the
     * JVM's partition if one is open: {@link CpuSet#inherit()} becomes its real-time CPUs for a
     * real-time request and its ordinary CPUs otherwise, and a thread put on a real-time CPU is
     * one the keeper leaves alone. Done under the partition's lock, so no sweep sees it half placed.
     *
     * @return the CPUs asked of the OS (inherit: none asked) and the OS's answer (null: none asked)
     */
    static Placed place(ThreadPolicy requested, CpuSet cpus) {
        synchronized (LOCK) {
            CpuSet resolved = cpus;
            if (current != null && current.keeper != null) {
                if (cpus.isInherit()) {
                    resolved = requested.isRealtime() ? current.realtimeCpus : current.ordinaryCpus;
                }
                int tid = LinuxNative.currentThreadId();
                if (Arrays.stream(resolved.cpus()).anyMatch(current.realtimeCpus::contains)) {
                    current.placed.add(tid);
                } else {
                    current.placed.remove(tid);
                }
            }
            releaseForRealtimeLocked(); // a configured thread may run, or be lent, a real-time policy
            return new Placed(resolved, resolved.isInherit() ? null : LinuxNative.setAffinity(0, resolved.cpus()));
        }
    }

    /**
     * For the calling thread that the platform configures, or whose real-time request the kernel
     * refused: marks it as one the keeper never puts in the ordinary cpu group (it may run, or be
     * lent, a real-time policy, which that group cannot grant), and takes it out of that group, or
     * out of one of ours it was born in (a partitioned parent JVM's), if it is in one.
     *
     * @return whether it moved the thread, so a refused request is worth asking again
     */
    static boolean releaseForRealtime() {
        synchronized (LOCK) {
            return releaseForRealtimeLocked();
        }
    }

    private static boolean releaseForRealtimeLocked() {
        if (!LinuxNative.isAvailable()) {
            return false;
        }
        if (CONFIGURED.size() >= CONFIGURED_PRUNE_AT) {
            CONFIGURED.retainAll(new HashSet<>(Shared.tasks()));
        }
        CONFIGURED.add(LinuxNative.currentThreadId());
        if (current != null && current.group != null) {
            return current.group.releaseCurrent();
        }
        return OrdinaryCpuGroup.leaveInherited();
    }

    /** What {@link #place} asked of the OS and got. */
    record Placed(CpuSet cpus, NativeResult result) {
    }

    /**
     * The CPUs of the real-time threads.
     *
     * @return the CPUs the partition was opened with
     */
    public CpuSet realtimeCpus() {
        return shared.realtimeCpus;
    }

    /**
     * The CPUs of every other thread.
     *
     * @return the opener's CPUs without the real-time ones; {@link CpuSet#inherit()} when the
     *         partition holds nothing
     */
    public CpuSet ordinaryCpus() {
        return shared.ordinaryCpus;
    }

    /**
     * What could not be done at start.
     *
     * @return the threads that could not be moved, or the one refusal of the whole partition; empty
     *         when everything was done
     */
    public List<PlatformRefusal> refusals() {
        return shared.refusals;
    }

    /**
     * The cpu cgroup of the JVM's ordinary threads, where one could be made: a cgroup v1 {@code cpu}
     * group {@code etherware-<pid>} under the process's own group, where the keeper puts every
     * ordinary thread the platform did not configure (those may run or be lent a real-time policy,
     * which that group cannot grant). Two JVMs on one machine then mostly stop waiting for each
     * other's threads to reach a safepoint (docs/REALTIME.md, section 4). Made and removed with the
     * partition; where it cannot be (cgroup v2, no permission, a process group without a real-time
     * budget), {@link #describe()} says why and the partition holds without it.
     *
     * @return the group's path in the cpu hierarchy, e.g. {@code /etherware-4242}; empty where none,
     *         or once the partition has closed
     */
    public java.util.Optional<String> ordinaryCpuGroup() {
        return shared.group == null || shared.stopped ? java.util.Optional.empty()
                : java.util.Optional.of(shared.group.ordinaryGroup());
    }

    /**
     * How many ordinary threads the keeper found on a real-time CPU and moved back.
     *
     * @return the count since the partition opened, over all holders
     */
    public long threadsMovedBack() {
        return shared.movedBack.get();
    }

    /**
     * The partition's state for reports.
     *
     * @return one line: the CPUs on each side and the threads moved and refused, or why the
     *         partition holds nothing
     */
    public String describe() {
        return shared.describe();
    }

    /**
     * Ends this holder's share (once; again does nothing). The last holder stops the keeper and
     * puts the threads the partition moved back, before another partition can open.
     */
    @Override
    public void close() {
        if (!closed.compareAndSet(false, true)) {
            return;
        }
        synchronized (LOCK) {
            if (--shared.holders > 0 || current != shared) {
                return;
            }
            shared.stopAndRestore();
            current = null;
        }
        if (shared.keeper != null) {
            LockSupport.unpark(shared.keeper); // it sees 'stopped' at its next look and ends
        }
    }

    /** The state every holder of one partition shares; every method is called with {@link #LOCK} held. */
    private static final class Shared {
        final CpuSet realtimeCpus;
        final CpuSet ordinaryCpus;
        /** The opener's CPUs and the real-time ones: where a thread without a recorded past goes back. */
        final CpuSet allCpus;
        final List<PlatformRefusal> refusals;
        final int threadsMovedAtStart;
        final AtomicLong movedBack = new AtomicLong();
        /** Kernel thread ids the platform put on a real-time CPU on request. */
        final Set<Integer> placed = new HashSet<>();
        /** Where each thread the first sweep moved was before, by kernel thread id. */
        final Map<Integer, int[]> previous = new HashMap<>();
        /** Kernel thread ids the keeper put in the ordinary group. */
        final Set<Integer> grouped = new HashSet<>();
        /** The ordinary threads' cpu group, or null where none could be made ({@link #groupNote}). */
        final OrdinaryCpuGroup group;
        final String groupNote;
        final Thread keeper;
        int holders = 1;
        volatile boolean stopped;

        Shared(CpuSet realtimeCpus, CpuSet ordinaryCpus, CpuSet allCpus) {
            this.realtimeCpus = realtimeCpus;
            this.ordinaryCpus = ordinaryCpus;
            this.allCpus = allCpus;
            OrdinaryCpuGroup.Outcome made = OrdinaryCpuGroup.create();
            this.group = made.group().orElse(null);
            this.groupNote = group != null ? "ordinary threads in " + group : "no cpu group (" + made.reason() + ")";
            var found = new ArrayList<PlatformRefusal>();
            this.threadsMovedAtStart = sweep(true, found);
            this.refusals = List.copyOf(found);
            // Started after the sweep: it inherits the ordinary CPUs from this thread.
            this.keeper = Thread.ofPlatform().daemon().name("etherware-cpu-partition").unstarted(this::keep);
            this.keeper.start();
        }

        private Shared(CpuSet realtimeCpus, PlatformRefusal refusal) {
            this.realtimeCpus = realtimeCpus;
            this.ordinaryCpus = CpuSet.inherit();
            this.allCpus = CpuSet.inherit();
            this.refusals = List.of(refusal);
            this.threadsMovedAtStart = 0;
            this.keeper = null;
            this.group = null;
            this.groupNote = "";
        }

        static Shared inert(CpuSet realtimeCpus, PlatformRefusal refusal) {
            return new Shared(realtimeCpus, refusal);
        }

        String describe() {
            if (keeper == null) {
                return "cpu partition: real-time CPUs " + realtimeCpus + " not partitioned [" + refusals.get(0) + "]";
            }
            return "cpu partition: real-time threads on " + realtimeCpus + ", every other thread on " + ordinaryCpus
                    + " (" + threadsMovedAtStart + " moved at start, " + refusals.size() + " refused, "
                    + movedBack.get() + " moved back since); " + groupNote;
        }

        private void keep() {
            boolean warned = false;
            while (true) {
                LockSupport.parkNanos(this, KEEPER_PERIOD_NS);
                var found = new ArrayList<PlatformRefusal>();
                synchronized (LOCK) {
                    if (stopped) {
                        return;
                    }
                    movedBack.addAndGet(sweep(false, found));
                }
                if (!found.isEmpty() && !warned) {
                    warned = true;
                    Platform.current().warnOnce(List.of(found.get(0)));
                }
            }
        }

        /** With the lock held: no sweep runs after this; the moved threads go back. */
        void stopAndRestore() {
            if (keeper == null) {
                return;
            }
            stopped = true;
            int restored = 0;
            for (int tid : tasks()) {
                NativeResult policy = LinuxNative.getScheduler(tid);
                int[] affinity = LinuxNative.getAffinity(tid);
                if (!policy.ok() || isRealtime(policy) || affinity == null
                        || !Arrays.equals(affinity, ordinaryCpus.cpus())) {
                    continue; // real-time, or moved by someone else since: not ours to undo
                }
                int[] target = previous.getOrDefault(tid, allCpus.cpus());
                if (LinuxNative.setAffinity(tid, target).ok()) {
                    restored++;
                }
            }
            previous.clear();
            placed.clear();
            grouped.clear();
            OrdinaryCpuGroup.Closed regrouped = group != null ? group.close() : null;
            LOG.info("cpu partition {} ended; {} threads back on the CPUs they had{}", realtimeCpus, restored,
                    regrouped != null ? ", " + regrouped.threadsMoved() + " back in cpu group " + group.realtimeGroup()
                            : "");
            if (regrouped != null && !regrouped.removed()) {
                LOG.warn("cpu partition {}: cpu group {} could not be removed (threads kept being born in it);"
                        + " the next partition of this JVM reuses it", realtimeCpus, group.ordinaryGroup());
            }
        }

        /**
         * With the lock held: moves the ordinary threads that may run on a real-time CPU to the
         * ordinary CPUs (remembering, in the first sweep, where each was), skipping real-time
         * threads and those placed on request, and forgets threads that have ended. Returns how
         * many moved.
         */
        private int sweep(boolean first, List<PlatformRefusal> refusalsOut) {
            List<Integer> tids = tasks();
            if (tids.isEmpty()) {
                refusalsOut.add(new PlatformRefusal("cpu affinity", "every ordinary thread to " + ordinaryCpus, 0, "",
                        "cannot list this process's threads in /proc/self/task"));
                return 0;
            }
            var alive = new HashSet<>(tids);
            placed.retainAll(alive);
            previous.keySet().retainAll(alive);
            CONFIGURED.retainAll(alive);
            grouped.retainAll(alive);
            int moved = 0;
            for (int tid : tids) {
                NativeResult policy = LinuxNative.getScheduler(tid);
                if (!policy.ok() || isRealtime(policy) || placed.contains(tid)) {
                    continue; // ended meanwhile, real-time, or placed on request: its CPUs are its own
                }
                if (group != null && !CONFIGURED.contains(tid) && grouped.add(tid) && !group.addOrdinary(tid)) {
                    grouped.remove(tid); // ended meanwhile, or refused: tried again at the next sweep
                }
                int[] affinity = LinuxNative.getAffinity(tid);
                if (affinity == null || Arrays.stream(affinity).noneMatch(realtimeCpus::contains)) {
                    continue;
                }
                NativeResult result = LinuxNative.setAffinity(tid, ordinaryCpus.cpus());
                if (result.ok()) {
                    if (first) {
                        previous.put(tid, affinity);
                    }
                    moved++;
                } else if (Files.exists(Path.of("/proc/self/task", Integer.toString(tid)))) {
                    refusalsOut.add(new PlatformRefusal("cpu affinity", "thread " + tid + " to " + ordinaryCpus,
                            result.errno(), Errno.name(result.errno()),
                            RefusalAdvice.forAffinity(ordinaryCpus, result.errno(), LinuxNative.getAffinity(tid))));
                }
            }
            return moved;
        }

        private static boolean isRealtime(NativeResult policy) {
            return policy.value() == LinuxNative.SCHED_FIFO || policy.value() == LinuxNative.SCHED_RR;
        }

        /** This process's kernel thread ids now; empty when they cannot be listed. */
        static List<Integer> tasks() {
            try (var entries = Files.list(Path.of("/proc/self/task"))) {
                return entries.map(task -> Integer.parseInt(task.getFileName().toString())).toList();
            } catch (IOException | RuntimeException e) {
                return List.of();
            }
        }
    }

    /** The online CPUs ({@code /sys/devices/system/cpu/online}), or null where unreadable. */
    private static int[] onlineCpus() {
        try {
            String text = Files.readString(Path.of("/sys/devices/system/cpu/online")).strip();
            return CpuSet.parse(text).cpus();
        } catch (IOException | RuntimeException e) {
            return null;
        }
    }
}
