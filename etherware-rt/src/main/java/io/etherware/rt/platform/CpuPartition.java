package io.etherware.rt.platform;

import io.etherware.rt.platform.internal.Errno;
import io.etherware.rt.platform.internal.LinuxNative;
import io.etherware.rt.platform.internal.NativeResult;
import io.etherware.rt.platform.internal.RefusalAdvice;
import java.io.IOException;
import java.nio.file.Files;
import java.nio.file.Path;
import java.util.ArrayList;
import java.util.Arrays;
import java.util.List;
import java.util.Map;
import java.util.Objects;
import java.util.Set;
import java.util.concurrent.ConcurrentHashMap;
import java.util.concurrent.atomic.AtomicBoolean;
import java.util.concurrent.atomic.AtomicLong;
import java.util.concurrent.locks.LockSupport;
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
 * <p>The real-time CPUs need not be among the opening thread's CPUs: a JVM started by a partitioned
 * one inherits only the ordinary CPUs, and still puts its real-time threads on the real-time ones.
 *
 * <p>One partition per JVM: {@link Platform#partitionCpus} with the same CPUs again gives another
 * holder of it, with other CPUs fails. Each holder closes once (a second close of the same holder
 * does nothing); when the last has closed, the keeper stops and the threads the partition moved go
 * back to the CPUs they had. Where the platform cannot set affinities (not Linux), the partition
 * holds nothing and says why in {@link #refusals()}. Thread-safe.
 */
public final class CpuPartition implements AutoCloseable {

    private static final Logger LOG = LoggerFactory.getLogger(CpuPartition.class);
    /** How often the keeper looks for ordinary threads on the real-time CPUs. */
    static final long KEEPER_PERIOD_NS = 1_000_000_000L;

    private static final Object LOCK = new Object();
    private static Shared current;

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
            if (!LinuxNative.isAvailable()) {
                PlatformRefusal refusal = new PlatformRefusal("cpu partition", realtimeCpus.toString(), Errno.ENOSYS,
                        Errno.name(Errno.ENOSYS), "CPU affinity needs Linux with native access ("
                        + LinuxNative.unavailableReason().orElse("") + "); the threads run on every CPU");
                Platform.current().warnOnce(List.of(refusal));
                return new CpuPartition(Shared.inert(realtimeCpus, refusal), true);
            }
            int[] allowed = LinuxNative.getAffinity(0);
            if (allowed == null || allowed.length == 0) {
                throw new IllegalStateException("realtimeCpus=" + realtimeCpus + ": cannot read this thread's CPUs");
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
            current = new Shared(realtimeCpus, CpuSet.of(ordinary));
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

    /** The CPUs of the real-time threads. */
    public CpuSet realtimeCpus() {
        return shared.realtimeCpus;
    }

    /** The CPUs of every other thread. */
    public CpuSet ordinaryCpus() {
        return shared.ordinaryCpus;
    }

    /** What could not be done at start: threads that could not be moved, or the whole partition. */
    public List<PlatformRefusal> refusals() {
        return shared.refusals;
    }

    /** Ordinary threads the keeper found on a real-time CPU and moved back, since start. */
    public long threadsMovedBack() {
        return shared.movedBack.get();
    }

    /** One line for reports. */
    public String describe() {
        return shared.describe();
    }

    /**
     * The CPUs a thread asking for {@code requested} on {@code cpus} gets under this partition.
     * Called on that thread, before it sets its affinity: a thread placed on a real-time CPU here is
     * one the keeper leaves alone.
     */
    CpuSet resolve(ThreadPolicy requested, CpuSet cpus) {
        CpuSet resolved = cpus.isInherit() ? (requested.isRealtime() ? shared.realtimeCpus : shared.ordinaryCpus)
                : cpus;
        if (Arrays.stream(resolved.cpus()).anyMatch(shared.realtimeCpus::contains)) {
            shared.placed.add(LinuxNative.currentThreadId());
        }
        return resolved;
    }

    /**
     * Ends this holder's share (once; again does nothing). The last holder stops the keeper and
     * puts the threads the partition moved back on the CPUs they had.
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
            current = null;
        }
        shared.stop();
    }

    /** The state every holder of one partition shares. */
    private static final class Shared {
        final CpuSet realtimeCpus;
        final CpuSet ordinaryCpus;
        final List<PlatformRefusal> refusals;
        final int threadsMovedAtStart;
        final AtomicLong movedBack = new AtomicLong();
        /** Kernel thread ids the platform put on a real-time CPU itself. */
        final Set<Integer> placed = ConcurrentHashMap.newKeySet();
        /** Where each thread the partition moved was before, by kernel thread id. */
        final Map<Integer, int[]> previous = new ConcurrentHashMap<>();
        final Thread keeper;
        int holders = 1; // guarded by LOCK
        volatile boolean stopped;

        Shared(CpuSet realtimeCpus, CpuSet ordinaryCpus) {
            this.realtimeCpus = realtimeCpus;
            this.ordinaryCpus = ordinaryCpus;
            var found = new ArrayList<PlatformRefusal>();
            this.threadsMovedAtStart = moveOrdinary(false, found);
            this.refusals = List.copyOf(found);
            // Started after the move: it inherits the ordinary CPUs from this thread.
            this.keeper = Thread.ofPlatform().daemon().name("etherware-cpu-partition").unstarted(this::keep);
            this.keeper.start();
        }

        private Shared(CpuSet realtimeCpus, PlatformRefusal refusal) {
            this.realtimeCpus = realtimeCpus;
            this.ordinaryCpus = CpuSet.inherit();
            this.refusals = List.of(refusal);
            this.threadsMovedAtStart = 0;
            this.keeper = null;
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
                    + movedBack.get() + " moved back since)";
        }

        void stop() {
            if (keeper == null) {
                return;
            }
            stopped = true;
            LockSupport.unpark(keeper);
            try {
                keeper.join(java.time.Duration.ofSeconds(2));
            } catch (InterruptedException e) {
                Thread.currentThread().interrupt();
            }
            synchronized (LOCK) {
                // A partition opened meanwhile (same CPUs) has placed the threads itself: leave them.
                if (current == null) {
                    moveOrdinary(true, new ArrayList<>());
                }
            }
            LOG.info("cpu partition {} ended; the threads it moved are back on the CPUs they had", realtimeCpus);
        }

        private void keep() {
            boolean warned = false;
            while (!stopped) {
                LockSupport.parkNanos(this, KEEPER_PERIOD_NS);
                if (!stopped) {
                    var found = new ArrayList<PlatformRefusal>();
                    movedBack.addAndGet(moveOrdinary(false, found));
                    if (!found.isEmpty() && !warned) {
                        warned = true;
                        Platform.current().warnOnce(List.of(found.get(0)));
                    }
                }
            }
        }

        /**
         * Moves the process's ordinary threads that may run on a real-time CPU to the ordinary
         * CPUs, remembering where each was, or ({@code release}) puts each thread it moved back
         * where it was, unless something else has moved it since. Skips real-time threads and
         * those the platform placed on purpose. Returns how many moved.
         */
        private int moveOrdinary(boolean release, List<PlatformRefusal> refusalsOut) {
            if (release) {
                int moved = 0;
                for (var entry : previous.entrySet()) {
                    int[] affinity = LinuxNative.getAffinity(entry.getKey());
                    if (affinity != null && Arrays.equals(affinity, ordinaryCpus.cpus())
                            && LinuxNative.setAffinity(entry.getKey(), entry.getValue()).ok()) {
                        moved++;
                    }
                }
                previous.clear();
                return moved;
            }
            Path tasks = Path.of("/proc/self/task");
            int moved = 0;
            try (var entries = Files.list(tasks)) {
                for (Path task : entries.toList()) {
                    int tid = Integer.parseInt(task.getFileName().toString());
                    NativeResult policy = LinuxNative.getScheduler(tid);
                    if (!policy.ok() || policy.value() == LinuxNative.SCHED_FIFO
                            || policy.value() == LinuxNative.SCHED_RR || placed.contains(tid)) {
                        continue; // ended meanwhile, real-time, or placed on purpose: its CPUs are its own
                    }
                    int[] affinity = LinuxNative.getAffinity(tid);
                    if (affinity == null || Arrays.stream(affinity).noneMatch(realtimeCpus::contains)) {
                        continue;
                    }
                    NativeResult result = LinuxNative.setAffinity(tid, ordinaryCpus.cpus());
                    if (result.ok()) {
                        previous.putIfAbsent(tid, affinity);
                        moved++;
                    } else if (Files.exists(task)) {
                        refusalsOut.add(new PlatformRefusal("cpu affinity", "thread " + tid + " to " + ordinaryCpus,
                                result.errno(), Errno.name(result.errno()),
                                RefusalAdvice.forAffinity(ordinaryCpus, result.errno(), LinuxNative.getAffinity(tid))));
                    }
                }
            } catch (IOException | RuntimeException e) {
                refusalsOut.add(new PlatformRefusal("cpu affinity", "every ordinary thread to " + ordinaryCpus, 0, "",
                        "cannot list this process's threads in " + tasks + ": " + e));
            }
            return moved;
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
