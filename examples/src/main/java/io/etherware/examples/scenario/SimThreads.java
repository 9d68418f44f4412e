package io.etherware.examples.scenario;

import io.etherware.rt.platform.CpuSet;
import io.etherware.rt.platform.Platform;
import io.etherware.rt.platform.ThreadGrant;
import io.etherware.rt.platform.ThreadPolicy;
import java.util.List;
import java.util.Objects;
import java.util.concurrent.CopyOnWriteArrayList;
import java.util.concurrent.ThreadFactory;
import java.util.concurrent.locks.LockSupport;
import org.slf4j.Logger;
import org.slf4j.LoggerFactory;

/**
 * Threads of the simulated physical world (the DSP board, the probe that watches the plant),
 * raised to a real-time priority from inside the JVM through {@link Platform}. The JVM's own load must not starve the world the controller acts on, whichever
 * scheduler the node uses; these threads sleep between their cycles and never spin.
 *
 * <p>Thread-safe. Each thread asks for its priority itself, as its first act; a refusal is warned
 * about once by {@link Platform} and the thread runs on at normal priority.
 */
public final class SimThreads {

    /** The DSP board: above every dispatcher of Table II (80/70/60) and the Notifier (81). */
    public static final int BOARD_PRIORITY = 90;
    /** The plant probe: just below the board, above the dispatchers. */
    public static final int PROBE_PRIORITY = 89;

    private static final Logger LOG = LoggerFactory.getLogger(SimThreads.class);

    private static final long POLL_NS = 1_000_000L;

    private final List<ThreadGrant> grants = new CopyOnWriteArrayList<>();
    private final CpuSet cpus;

    /** Threads on every CPU. */
    public SimThreads() {
        this(CpuSet.inherit());
    }

    /** Threads on {@code cpus} (a real-time partition), or every CPU for {@link CpuSet#inherit()}. */
    public SimThreads(CpuSet cpus) {
        this.cpus = Objects.requireNonNull(cpus, "cpus");
    }

    /**
     * A factory of daemon platform threads named {@code name} that run at SCHED_FIFO
     * {@code priority} on this factory's CPUs.
     */
    public ThreadFactory fifo(String name, int priority) {
        Objects.requireNonNull(name, "name");
        ThreadPolicy policy = ThreadPolicy.fifo(priority);
        return runnable -> Thread.ofPlatform().name(name).daemon().unstarted(() -> {
            ThreadGrant grant = Platform.current().configureCurrentThread(policy, cpus);
            grants.add(grant);
            LOG.debug("{}", grant.toLine());
            runnable.run();
        });
    }

    /**
     * Waits until {@code count} threads of this factory have asked for their priority, or
     * {@code timeoutNs} passed.
     *
     * @return whether they all had
     */
    public boolean awaitConfigured(int count, long timeoutNs) {
        long deadlineNs = System.nanoTime() + timeoutNs;
        while (grants.size() < count) {
            long remainingNs = deadlineNs - System.nanoTime();
            if (remainingNs <= 0) {
                LOG.warn("only {} of {} real-time threads started within {} ms", grants.size(), count,
                        timeoutNs / 1_000_000);
                return false;
            }
            LockSupport.parkNanos(Math.min(remainingNs, POLL_NS));
        }
        return true;
    }

    /**
     * Waits up to {@code timeoutMs} for {@code thread} to end; an interrupt ends the wait and stays
     * set for the caller (for {@code close()} methods, which must not throw it).
     */
    public static void join(Thread thread, long timeoutMs) {
        try {
            thread.join(timeoutMs);
        } catch (InterruptedException e) {
            Thread.currentThread().interrupt();
        }
    }

    /** What the OS granted each thread made so far, in start order. */
    public List<ThreadGrant> grants() {
        return List.copyOf(grants);
    }

    /** Whether every thread made so far got the policy it asked for. */
    public boolean allGranted() {
        return grants.stream().allMatch(ThreadGrant::isPolicyGranted);
    }
}
