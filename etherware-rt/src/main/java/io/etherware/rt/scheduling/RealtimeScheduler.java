package io.etherware.rt.scheduling;

import io.etherware.core.scheduler.Job;
import io.etherware.core.scheduler.JobRunner;
import io.etherware.core.scheduler.Scheduler;
import io.etherware.core.time.NodeClock;
import io.etherware.rt.platform.Platform;
import io.etherware.rt.platform.PlatformRefusal;
import io.etherware.rt.platform.CpuLatencyHold;
import io.etherware.rt.platform.CpuPartition;
import io.etherware.rt.platform.PlatformReport;
import io.etherware.rt.platform.ThreadGrant;
import io.etherware.rt.scheduling.internal.ComponentRecorder;
import io.etherware.rt.scheduling.internal.DispatchContext;
import io.etherware.rt.scheduling.internal.Dispatcher;
import io.etherware.rt.scheduling.internal.DispatcherRecorder;
import java.util.ArrayList;
import java.util.Comparator;
import java.util.List;
import java.util.Objects;
import java.util.Optional;
import java.util.concurrent.ConcurrentHashMap;
import java.util.concurrent.ConcurrentMap;
import java.util.concurrent.TimeUnit;
import java.util.concurrent.atomic.AtomicBoolean;
import java.util.concurrent.locks.LockSupport;
import org.slf4j.Logger;
import org.slf4j.LoggerFactory;

/**
 * The Dispatching Module of paper Section IV-B (Fig. 4): N dispatchers, each a platform thread at
 * the OS priority its {@link ThreadSchedulingRule} gives it, each with its own priority queue;
 * a {@link JobPlacementRule} decides for every job which dispatcher runs it and with which key.
 * Preemption happens between dispatchers, by OS priority; within a dispatcher, jobs run one after
 * the other, smallest key first, ties by arrival.
 *
 * <p>With the default configuration (Table II and Algorithm 1) a HIGH message to component A
 * never waits for LOW work on component B: they run on different threads, and the HIGH one's
 * thread has the higher SCHED_FIFO priority.
 *
 * <p><b>What a HIGH message may wait for</b> (the priority inversion bound). One component handles
 * one message at a time (design decision 3). When a HIGH message arrives for a component that is
 * running a lower-criticality message on another dispatcher, the kernel parks it with the
 * component; it then waits for the rest of that one message's handling, at most that handler's
 * WCET, and nothing else: with priority inheritance (default on) the component's current
 * dispatcher runs at the HIGH priority meanwhile, so middle-priority work cannot stretch the wait;
 * and when the component frees up, the kernel hands it the most urgent waiting job by
 * {@link #urgency()}, so the HIGH message goes before other waiting lower ones. A HIGH message also
 * waits, as on any fixed-priority system, for the HIGH jobs before it on its own dispatcher.
 *
 * <p>Lifecycle and threading: construct, {@link #start} once, {@link #submit} from any thread
 * (including dispatcher threads), {@link #shutdown} once. {@link #stats()}, {@link #admission()}
 * and {@link #platformReport()} are thread-safe.
 */
public final class RealtimeScheduler implements Scheduler {

    private static final Logger LOG = LoggerFactory.getLogger(RealtimeScheduler.class);
    private static final long START_TIMEOUT_NS = TimeUnit.SECONDS.toNanos(10);
    private static final long MIN_JOIN_NS = TimeUnit.MILLISECONDS.toNanos(100);

    private final RealtimeSchedulerConfig config;
    private final List<DispatcherRecorder> recorders = new ArrayList<>();
    private final ConcurrentMap<String, ComponentRecorder> components = new ConcurrentHashMap<>();
    private final SchedulerStats stats;
    private final AdmissionControl admission;
    private final Comparator<Job> urgency;
    private final AtomicBoolean badPlacementLogged = new AtomicBoolean();
    private final Object lifecycle = new Object();
    private volatile DispatchContext context;
    /** {@link #name()}, then {@code @nodeId} once started by a node: what logs and thread names say. */
    private volatile String label;
    private volatile Dispatcher[] dispatchers;
    private volatile PlatformReport platformReport = new PlatformReport(List.of(), false, Optional.empty());
    private boolean shutDown;
    private CpuLatencyHold cpuLatency = CpuLatencyHold.none();
    private CpuPartition partition;

    /**
     * A scheduler that is not started yet: no thread runs and nothing is asked of the OS until
     * {@link #start}. Its {@link #stats()} and {@link #admission()} can be used already.
     *
     * @param config the validated configuration
     * @throws NullPointerException when {@code config} is null
     */
    public RealtimeScheduler(RealtimeSchedulerConfig config) {
        this.config = Objects.requireNonNull(config, "config");
        ThreadSchedulingRule tsr = config.threadSchedulingRule();
        for (int i = 0; i < tsr.size(); i++) {
            recorders.add(new DispatcherRecorder());
        }
        this.stats = new SchedulerStats(recorders, components);
        this.admission = new AdmissionControl(config.placementRule(), tsr.size(), config.admissionMode());
        this.urgency = urgencyOf(tsr);
    }

    /**
     * A scheduler with {@link RealtimeSchedulerConfig#defaults()}: Table II and Algorithm 1.
     *
     * @return a new scheduler, not started
     */
    public static RealtimeScheduler withDefaults() {
        return new RealtimeScheduler(RealtimeSchedulerConfig.defaults());
    }

    /**
     * The configured name, also the prefix of the dispatcher threads' names.
     *
     * @return e.g. {@code rt}
     */
    @Override
    public String name() {
        return config.name();
    }

    /** The name with the node id once a node started it ({@code rt@plant}), as logs show it. */
    private String label() {
        String current = label;
        return current != null ? current : name();
    }

    /**
     * The configuration this scheduler was built with.
     *
     * @return the configuration
     */
    public RealtimeSchedulerConfig config() {
        return config;
    }

    /**
     * Locks memory if configured, starts the dispatcher threads, waits until each has asked the OS
     * for its priority and CPUs, warns once per kind of refusal (quoting the most demanding
     * dispatcher), and logs the {@link PlatformReport}, one line per dispatcher. Refusals of the
     * OS never throw. A start that throws leaves no dispatcher running and nothing held.
     *
     * @param runner the kernel's delivery callback, called on the dispatcher threads
     * @param clock  the node's clock; dispatchers read its monotonic time
     * @throws IllegalStateException    when the scheduler was already started or shut down, a
     *                                  dispatcher did not start within 10 s, the calling thread was
     *                                  interrupted meanwhile, or another CPU partition is open
     * @throws IllegalArgumentException when the configured real-time CPUs cannot be partitioned
     */
    @Override
    public void start(JobRunner runner, NodeClock clock) {
        synchronized (lifecycle) {
            if (context != null || shutDown) {
                throw new IllegalStateException("scheduler " + name() + " was already started");
            }
            Optional<PlatformRefusal> memoryRefusal = config.lockMemory() ? Platform.current().lockMemory()
                    : Optional.empty();
            DispatchContext newContext = null;
            Dispatcher[] all = null;
            String node = runner.nodeId();
            String suffix = node == null || node.isEmpty() ? "" : "@" + node;
            label = name() + suffix;
            try {
                var processLines = new ArrayList<String>();
                var processRefusals = new ArrayList<PlatformRefusal>();
                ThreadSchedulingRule tsr = config.threadSchedulingRule();
                boolean anyRealtime = tsr.dispatchers().stream().anyMatch(spec -> spec.policy().isRealtime());
                if (config.holdCpuLatency() && anyRealtime) {
                    cpuLatency = CpuLatencyHold.request();
                    processLines.add(cpuLatency.state());
                    cpuLatency.refusal().ifPresent(processRefusals::add);
                }
                if (!config.realtimeCpus().isInherit()) {
                    // Before the dispatchers start: they, and every thread asking for a real-time
                    // policy on inherited CPUs from now on, take the real-time CPUs.
                    partition = Platform.current().partitionCpus(config.realtimeCpus());
                    processLines.add(partition.describe());
                    processRefusals.addAll(partition.refusals());
                }
                newContext = new DispatchContext(runner, clock, components, config.deadlineMissHandler(),
                        config.priorityInheritance());
                all = new Dispatcher[tsr.size()];
                for (int id = 0; id < all.length; id++) {
                    all[id] = new Dispatcher(id, tsr.dispatcher(id), newContext, recorders.get(id),
                            name() + "-dispatcher-" + id + suffix);
                }
                newContext.setDispatchers(all);
                // One at a time: each does its first-time work at its inherited priority, then takes
                // its real-time one, while the ones before it are parked. Started together, two that
                // had switched once burned both CPUs of a 2-core machine for 11 minutes while the
                // third, still ordinary, and the starting thread got only the kernel's real-time
                // throttling remainder: a real-time thread that spins for anything an ordinary
                // thread holds starves it.
                var grants = new ArrayList<ThreadGrant>();
                long deadlineNs = System.nanoTime() + START_TIMEOUT_NS;
                for (Dispatcher dispatcher : all) {
                    dispatcher.start();
                    grants.add(awaitGrant(dispatcher, deadlineNs));
                }
                warnMostDemandingFirst(grants);
                platformReport = new PlatformReport(grants, config.lockMemory(), memoryRefusal, processLines,
                        processRefusals);
                dispatchers = all;
                context = newContext;
                LOG.info("scheduler {}: placement {}, {} dispatchers {}", label(), config.placementRule(), all.length,
                        tsr);
                platformReport.lines().forEach(line -> LOG.info("scheduler {}: {}", label(), line));
            } catch (RuntimeException | Error e) {
                abortStarted(newContext, all); // a start that fails leaves no dispatcher running
                releaseProcessRequests(); // and holds nothing
                throw e;
            }
        }
    }

    /**
     * One warning per kind of refusal for all dispatchers, quoting the highest priority refused:
     * advice to raise RLIMIT_RTPRIO to dispatcher 3's 60 would leave dispatchers 1 and 2 (80, 70)
     * refused on the next start. Each dispatcher's own refusal stays in its report line.
     */
    private static void warnMostDemandingFirst(List<ThreadGrant> grants) {
        grants.stream()
                .sorted(Comparator.comparingInt((ThreadGrant grant) -> grant.requested().priority()).reversed())
                .forEach(grant -> Platform.current().warnOnce(grant.refusals()));
    }

    private static ThreadGrant awaitGrant(Dispatcher dispatcher, long deadlineNs) {
        try {
            ThreadGrant grant = dispatcher.awaitGrant(Math.max(0, deadlineNs - System.nanoTime()));
            if (grant == null) {
                throw new IllegalStateException("dispatcher " + dispatcher.id() + " did not start within "
                        + TimeUnit.NANOSECONDS.toSeconds(START_TIMEOUT_NS) + " s");
            }
            return grant;
        } catch (InterruptedException e) {
            Thread.currentThread().interrupt();
            throw new IllegalStateException("interrupted while starting dispatcher " + dispatcher.id(), e);
        }
    }

    /**
     * Places the job (unless it already has a placement: a parked job coming back keeps its own)
     * and queues it on its dispatcher. Lock-free; wakes the dispatcher only if it is idle. A
     * placement rule that throws or names a dispatcher that does not exist is logged once, and
     * the job runs on dispatcher 0 in arrival order.
     *
     * @param job the job; callable from any thread, including dispatcher threads
     * @return false when the scheduler is shutting down or shut down and did not take the job (a job
     *         that holds its component's reservation is still taken while draining); true otherwise
     * @throws IllegalStateException before {@link #start}
     */
    @Override
    public boolean submit(Job job) {
        DispatchContext started = context;
        if (started == null) {
            throw new IllegalStateException("scheduler " + name() + " is not started: call start(runner, clock) first");
        }
        Dispatcher[] all = dispatchers;
        if (!job.isPlaced()) {
            place(job, started.clock().nanoTime(), all.length);
        }
        int dispatcherId = job.dispatcherId();
        if (dispatcherId >= all.length) {
            logBadPlacement(job, "was placed on dispatcher " + dispatcherId + " by another scheduler");
            dispatcherId = 0;
        }
        return all[dispatcherId].offer(job);
    }

    private void place(Job job, long nowNs, int dispatcherCount) {
        Placement placement;
        try {
            placement = config.placementRule().place(job, nowNs);
        } catch (RuntimeException e) {
            logBadPlacement(job, "made placement rule " + config.placementRule().name() + " throw " + e);
            placement = null;
        }
        if (placement == null || placement.dispatcherId() >= dispatcherCount) {
            if (placement != null) {
                logBadPlacement(job, "was placed on dispatcher " + placement.dispatcherId() + " by "
                        + config.placementRule().name() + ", but there are " + dispatcherCount);
            }
            // Never lose the message for a policy bug: run it in arrival order on dispatcher 0.
            placement = new Placement(0, nowNs);
        }
        job.place(placement.dispatcherId(), placement.key());
    }

    private void logBadPlacement(Job job, String what) {
        if (badPlacementLogged.compareAndSet(false, true)) {
            LOG.error("scheduler {}: {} {}; running it (and any later such job) on dispatcher 0", label(), job, what);
        }
    }

    /**
     * Higher-priority dispatcher first (by the TSR), then smaller key, then earlier arrival.
     *
     * @return the order, most urgent first; the same allocation-free comparator on every call
     */
    @Override
    public Comparator<Job> urgency() {
        return urgency;
    }

    private static Comparator<Job> urgencyOf(ThreadSchedulingRule tsr) {
        int[] rank = new int[tsr.size()];
        for (int id = 0; id < rank.length; id++) {
            rank[id] = tsr.rank(id);
        }
        return (a, b) -> {
            int byRank = Integer.compare(rankOf(b, rank), rankOf(a, rank));
            if (byRank != 0) {
                return byRank;
            }
            int byKey = Long.compare(a.key(), b.key());
            return byKey != 0 ? byKey : Long.compare(a.sequence(), b.sequence());
        };
    }

    private static int rankOf(Job job, int[] rank) {
        int id = job.dispatcherId();
        return id >= 0 && id < rank.length ? rank[id] : -1;
    }

    /**
     * Stops taking new jobs (jobs that already hold their component's reservation are still
     * taken), lets the dispatchers run what is queued until nothing is queued or running, for at
     * most {@code timeoutNs}, then stops them (interrupting a dispatcher still inside a job), and
     * releases the CPU latency request and the CPU partition. Blocks the calling thread for up to
     * {@code timeoutNs}, plus a few hundred milliseconds when a dispatcher is stuck inside a job;
     * call it from a thread other than the dispatchers.
     *
     * @param timeoutNs how long the dispatchers may drain, in nanoseconds; a negative value is 0
     * @return the jobs that were queued but never run, so the kernel can count them as discarded;
     *         empty on a second call or when never started
     */
    @Override
    public List<Job> shutdown(long timeoutNs) {
        DispatchContext started;
        Dispatcher[] all;
        synchronized (lifecycle) {
            if (shutDown) {
                return List.of();
            }
            shutDown = true;
            started = context;
            all = dispatchers;
        }
        if (started == null) {
            releaseProcessRequests();
            return List.of();
        }
        long deadlineNs = System.nanoTime() + Math.max(0, timeoutNs);
        started.setState(DispatchContext.DRAINING);
        while (!started.isQuiet() && System.nanoTime() < deadlineNs) {
            LockSupport.parkNanos(TimeUnit.MILLISECONDS.toNanos(1));
        }
        started.setState(DispatchContext.ABORTED);
        for (Dispatcher dispatcher : all) {
            dispatcher.wake();
        }
        for (Dispatcher dispatcher : all) {
            join(dispatcher, Math.max(MIN_JOIN_NS, deadlineNs - System.nanoTime()));
        }
        var leftovers = new ArrayList<Job>();
        int[] stranded = {0};
        long settleUntilNs = System.nanoTime() + MIN_JOIN_NS;
        do {
            for (Dispatcher dispatcher : all) {
                leftovers.addAll(dispatcher.drain(stranded));
            }
            // A submitter that saw RUNNING just before the abort may still be adding its job.
        } while (started.unaccounted(leftovers.size() + stranded[0]) > 0 && System.nanoTime() < settleUntilNs
                && sleepBriefly());
        if (stranded[0] > 0) {
            LOG.warn("scheduler {}: {} queued jobs stay with dispatchers still inside a job after shutdown", label(),
                    stranded[0]);
        }
        releaseProcessRequests();
        LOG.info("scheduler {} stopped; {} queued jobs not run", label(), leftovers.size());
        return leftovers;
    }

    /** After a failed start: stops the dispatchers that did start. */
    private void abortStarted(DispatchContext newContext, Dispatcher[] all) {
        if (newContext == null || all == null) {
            return;
        }
        newContext.setState(DispatchContext.ABORTED);
        for (Dispatcher dispatcher : all) {
            if (dispatcher != null && dispatcher.thread() != null) {
                dispatcher.wake();
                join(dispatcher, MIN_JOIN_NS);
            }
        }
    }

    /** Releases the CPU latency request and this scheduler's share of the CPU partition. Idempotent. */
    private void releaseProcessRequests() {
        synchronized (lifecycle) {
            cpuLatency.close();
            cpuLatency = CpuLatencyHold.none();
            if (partition != null) {
                partition.close();
                partition = null;
            }
        }
    }

    private void join(Dispatcher dispatcher, long timeoutNs) {
        Thread thread = dispatcher.thread();
        try {
            if (!thread.join(java.time.Duration.ofNanos(timeoutNs))) {
                thread.interrupt();
                if (!thread.join(java.time.Duration.ofNanos(MIN_JOIN_NS))) {
                    LOG.warn("scheduler {}: dispatcher {} is still inside a job after shutdown; leaving it", label(),
                            dispatcher.id());
                }
            }
        } catch (InterruptedException e) {
            Thread.currentThread().interrupt();
        }
    }

    private static boolean sleepBriefly() {
        LockSupport.parkNanos(TimeUnit.MILLISECONDS.toNanos(1));
        return true;
    }

    /**
     * Time accounting, live. Available before start (all zero).
     *
     * @return the same thread-safe view on every call
     */
    public SchedulerStats stats() {
        return stats;
    }

    /**
     * Admission control for declared periodic streams, usable before and after start.
     *
     * @return the same thread-safe instance on every call
     */
    public AdmissionControl admission() {
        return admission;
    }

    /**
     * What each dispatcher asked of the OS and got.
     *
     * @return the report of the last successful start; empty before {@link #start}
     */
    public PlatformReport platformReport() {
        return platformReport;
    }
}
