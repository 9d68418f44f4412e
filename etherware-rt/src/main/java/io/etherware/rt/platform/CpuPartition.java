package io.etherware.rt.platform;

import io.etherware.rt.platform.internal.LinuxNative;
import io.etherware.rt.platform.internal.NativeResult;
import io.etherware.rt.platform.internal.RefusalAdvice;
import java.io.IOException;
import java.nio.file.Files;
import java.nio.file.Path;
import java.util.ArrayList;
import java.util.Arrays;
import java.util.List;
import java.util.Objects;
import java.util.concurrent.atomic.AtomicLong;
import java.util.concurrent.locks.LockSupport;
import org.slf4j.Logger;
import org.slf4j.LoggerFactory;

/**
 * The JVM's CPUs split in two: the real-time CPUs, for the threads that run at a real-time policy
 * (dispatchers, Notifier, network threads, a plant's board), and the ordinary CPUs, for every other
 * thread of the JVM, its own included (JIT compilers, collector threads, ordinary Java threads).
 *
 * <p>Why: a HotSpot safepoint (every collection, deoptimization, many JVM operations) waits until
 * every Java thread has stopped, and an ordinary thread that a real-time thread keeps off its CPU
 * reaches the safepoint only when it runs again, which under a stress task can be tens of
 * milliseconds while every real-time thread stands still. With the ordinary threads on other CPUs,
 * nothing runnable waits behind a real-time thread.
 *
 * <p>What it does, from {@link Platform#partitionCpus}: moves every thread of the process to the
 * ordinary CPUs; from then on {@link Platform#configureCurrentThread} gives a thread that asks for
 * {@link CpuSet#inherit()} the real-time CPUs when it asks for a real-time policy and the ordinary
 * CPUs otherwise; and a keeper thread (ordinary, on the ordinary CPUs) looks once a second for
 * ordinary threads that landed on a real-time CPU and moves them back. They land there because
 * Linux gives a new thread its creator's affinity: a pool thread started lazily from a dispatcher,
 * say. {@link #threadsMovedBack()} counts them.
 *
 * <p>One partition per JVM: a second {@link Platform#partitionCpus} with the same CPUs shares it,
 * with other CPUs fails. {@link #close()} by the last holder stops the keeper and lets the ordinary
 * threads on every CPU again. Thread-safe.
 */
public final class CpuPartition implements AutoCloseable {

    private static final Logger LOG = LoggerFactory.getLogger(CpuPartition.class);
    /** How often the keeper looks for ordinary threads on the real-time CPUs. */
    static final long KEEPER_PERIOD_NS = 1_000_000_000L;

    private static final Object LOCK = new Object();
    private static CpuPartition current;

    private final CpuSet realtimeCpus;
    private final CpuSet ordinaryCpus;
    private final CpuSet allCpus;
    private final List<PlatformRefusal> refusals;
    private final int threadsMovedAtStart;
    private final AtomicLong movedBack = new AtomicLong();
    private final Thread keeper;
    private int holders;
    private volatile boolean closed;

    private CpuPartition(CpuSet realtimeCpus, CpuSet ordinaryCpus, CpuSet allCpus) {
        this.realtimeCpus = realtimeCpus;
        this.ordinaryCpus = ordinaryCpus;
        this.allCpus = allCpus;
        var found = new ArrayList<PlatformRefusal>();
        this.threadsMovedAtStart = moveOrdinary(false, found);
        this.refusals = List.copyOf(found);
        this.keeper = Thread.ofPlatform().daemon().name("etherware-cpu-partition").unstarted(this::keep);
        this.keeper.start();
    }

    /** Opens the partition, or shares the JVM's one when it has the same real-time CPUs. */
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
                return current;
            }
            int[] allowed = LinuxNative.getAffinity(0);
            if (allowed == null || allowed.length == 0) {
                throw new IllegalStateException("realtimeCpus=" + realtimeCpus + ": cannot read this thread's CPUs ("
                        + LinuxNative.unavailableReason().orElse("sched_getaffinity failed") + ")");
            }
            int[] ordinary = Arrays.stream(allowed).filter(cpu -> !realtimeCpus.contains(cpu)).toArray();
            for (int cpu : realtimeCpus.cpus()) {
                if (Arrays.stream(allowed).noneMatch(allowedCpu -> allowedCpu == cpu)) {
                    throw new IllegalArgumentException("realtimeCpus=" + realtimeCpus + ": CPU " + cpu
                            + " is not among this process's CPUs " + CpuSet.of(allowed));
                }
            }
            if (ordinary.length == 0) {
                throw new IllegalArgumentException("realtimeCpus=" + realtimeCpus + " leaves no CPU of "
                        + CpuSet.of(allowed) + " for the JVM's other threads; keep at least one out of it");
            }
            current = new CpuPartition(realtimeCpus, CpuSet.of(ordinary), CpuSet.of(allowed));
            current.holders = 1;
            LOG.info("{}", current.describe());
            if (!current.refusals.isEmpty()) {
                Platform.current().warnOnce(List.of(current.refusals.get(0)));
            }
            return current;
        }
    }

    /** The JVM's partition, or null. */
    static CpuPartition current() {
        synchronized (LOCK) {
            return current;
        }
    }

    /** The CPUs of the real-time threads. */
    public CpuSet realtimeCpus() {
        return realtimeCpus;
    }

    /** The CPUs of every other thread. */
    public CpuSet ordinaryCpus() {
        return ordinaryCpus;
    }

    /** Threads that could not be moved off the real-time CPUs at start (one that ended is not one). */
    public List<PlatformRefusal> refusals() {
        return refusals;
    }

    /** Ordinary threads the keeper found on a real-time CPU and moved back, since start. */
    public long threadsMovedBack() {
        return movedBack.get();
    }

    /** One line for reports. */
    public String describe() {
        return "cpu partition: real-time threads on " + realtimeCpus + ", every other thread on " + ordinaryCpus
                + " (" + threadsMovedAtStart + " moved at start, " + refusals.size() + " refused, "
                + movedBack.get() + " moved back since)";
    }

    /** The CPUs a thread asking for {@code requested} on {@code cpus} gets under this partition. */
    CpuSet resolve(ThreadPolicy requested, CpuSet cpus) {
        if (!cpus.isInherit()) {
            return cpus;
        }
        return requested.isRealtime() ? realtimeCpus : ordinaryCpus;
    }

    /** Ends this holder's share; the last one stops the keeper and lets ordinary threads use every CPU. */
    @Override
    public void close() {
        synchronized (LOCK) {
            if (current != this || --holders > 0) {
                return;
            }
            current = null;
            closed = true;
        }
        LockSupport.unpark(keeper);
        try {
            keeper.join(java.time.Duration.ofSeconds(2));
        } catch (InterruptedException e) {
            Thread.currentThread().interrupt();
        }
        moveOrdinary(true, new ArrayList<>());
        LOG.info("cpu partition {} ended; ordinary threads may run on {} again", realtimeCpus, allCpus);
    }

    private void keep() {
        while (!closed) {
            LockSupport.parkNanos(this, KEEPER_PERIOD_NS);
            if (!closed) {
                movedBack.addAndGet(moveOrdinary(false, new ArrayList<>()));
            }
        }
    }

    /**
     * Moves the process's ordinary threads: to the ordinary CPUs those that may run on a real-time
     * CPU ({@code release} false), or back to every CPU ({@code release} true). Returns how many moved.
     */
    private int moveOrdinary(boolean release, List<PlatformRefusal> refusalsOut) {
        Path tasks = Path.of("/proc/self/task");
        int moved = 0;
        try (var entries = Files.list(tasks)) {
            for (Path task : entries.toList()) {
                int tid = Integer.parseInt(task.getFileName().toString());
                NativeResult policy = LinuxNative.getScheduler(tid);
                if (!policy.ok() || policy.value() == LinuxNative.SCHED_FIFO || policy.value() == LinuxNative.SCHED_RR) {
                    continue; // ended meanwhile, or real-time: its CPUs are its own
                }
                int[] affinity = LinuxNative.getAffinity(tid);
                if (affinity == null) {
                    continue;
                }
                boolean onRealtime = Arrays.stream(affinity).anyMatch(realtimeCpus::contains);
                if (release ? !Arrays.equals(affinity, ordinaryCpus.cpus()) : !onRealtime) {
                    continue; // released: only what the partition put on the ordinary CPUs goes back
                }
                CpuSet target = release ? allCpus : ordinaryCpus;
                NativeResult result = LinuxNative.setAffinity(tid, target.cpus());
                if (result.ok()) {
                    moved++;
                } else if (Files.exists(task)) {
                    refusalsOut.add(new PlatformRefusal("cpu affinity", "thread " + tid + " to " + target,
                            result.errno(), io.etherware.rt.platform.internal.Errno.name(result.errno()),
                            RefusalAdvice.forAffinity(target, result.errno(), LinuxNative.getAffinity(tid))));
                }
            }
        } catch (IOException | RuntimeException e) {
            refusalsOut.add(new PlatformRefusal("cpu affinity", "every ordinary thread to " + ordinaryCpus, 0, "",
                    "cannot list this process's threads in " + tasks + ": " + e));
        }
        return moved;
    }
}
