package io.etherware.rt.scheduling;

import static io.etherware.rt.scheduling.TestJobs.job;
import static org.junit.jupiter.api.Assertions.assertEquals;
import static org.junit.jupiter.api.Assertions.assertFalse;
import static org.junit.jupiter.api.Assertions.assertThrows;
import static org.junit.jupiter.api.Assertions.assertTrue;

import io.etherware.core.message.Criticality;
import io.etherware.core.message.QoS;
import io.etherware.core.scheduler.Job;
import io.etherware.core.time.NodeClock;
import io.etherware.rt.platform.OsThreadStat;
import io.etherware.rt.platform.Platform;
import io.etherware.rt.platform.ThreadGrant;
import io.etherware.rt.platform.ThreadPolicy;
import io.etherware.testkit.ManualClock;
import java.nio.file.Files;
import java.nio.file.Path;
import java.util.ArrayList;
import java.util.Collections;
import java.util.List;
import java.util.Map;
import java.util.concurrent.ConcurrentHashMap;
import java.util.concurrent.CopyOnWriteArrayList;
import java.util.concurrent.CountDownLatch;
import java.util.concurrent.LinkedBlockingQueue;
import java.util.concurrent.TimeUnit;
import jdk.jfr.Recording;
import jdk.jfr.consumer.RecordedEvent;
import jdk.jfr.consumer.RecordingFile;
import org.junit.jupiter.api.AfterEach;
import org.junit.jupiter.api.Test;
import org.junit.jupiter.api.io.TempDir;

/**
 * The Dispatching Module at the SPI level, with a fake runner in place of the kernel. Dispatchers
 * are SCHED_OTHER here: these tests are about order and accounting, not OS priority.
 */
class RealtimeSchedulerTest {

    private static final long MS = 1_000_000L;
    /** Where the manual clocks start: an arbitrary origin, as System.nanoTime's is. */
    private static final long CLOCK_START_NS = 1_000 * MS;
    private RealtimeScheduler scheduler;

    @AfterEach
    void stop() {
        if (scheduler != null) {
            scheduler.shutdown(TimeUnit.SECONDS.toNanos(1));
        }
    }

    private RealtimeScheduler start(RealtimeSchedulerConfig config, io.etherware.core.scheduler.JobRunner runner,
                                    NodeClock clock) {
        scheduler = new RealtimeScheduler(config);
        scheduler.start(runner, clock);
        return scheduler;
    }

    private static RealtimeSchedulerConfig.Builder oneDispatcher(JobPlacementRule rule) {
        return RealtimeSchedulerConfig.builder().threadSchedulingRule(ThreadSchedulingRule.nonRealtime(1))
                .placementRule(rule);
    }

    /** A rule that reads the key from a table, for exact control of the queue order. */
    private static JobPlacementRule keyTable(Map<Long, Long> keyBySequence) {
        return rule("key-table", 1, QueuePolicy.EARLIEST_DEADLINE_FIRST,
                job -> new Placement(0, keyBySequence.getOrDefault(job.sequence(), Long.MIN_VALUE)));
    }

    /** A placement rule made of its parts. */
    private static JobPlacementRule rule(String name, int dispatchers, QueuePolicy policy,
                                         java.util.function.Function<Job, Placement> placement) {
        return new JobPlacementRule() {
            @Override
            public Placement place(Job job, long nowNs) {
                return placement.apply(job);
            }

            @Override
            public int dispatchersRequired() {
                return dispatchers;
            }

            @Override
            public QueuePolicy queuePolicy(int dispatcherId) {
                return policy;
            }

            @Override
            public String name() {
                return name;
            }
        };
    }

    @Test
    void shouldPartitionTheCpusWhileRunningAndReleaseThePartitionAndTheCpuLatencyAtShutdown() {
        int[] allowed = io.etherware.rt.platform.internal.LinuxNative.getAffinity(0);
        org.junit.jupiter.api.Assumptions.assumeTrue(Platform.current().isAvailable() && allowed.length >= 2,
                "needs Linux and two CPUs");
        io.etherware.rt.platform.CpuSet realtime = io.etherware.rt.platform.CpuSet.of(allowed[allowed.length - 1]);
        // One SCHED_OTHER dispatcher: holdCpuLatency applies only with a real-time one, so none here.
        start(oneDispatcher(new FifoPlacement()).realtimeCpus(realtime).build(), (job, nowNs) -> true,
                NodeClock.system());
        assertEquals(realtime, Platform.current().cpuPartition().orElseThrow().realtimeCpus());
        List<String> lines = scheduler.platformReport().lines();
        assertTrue(lines.getLast().startsWith("cpu partition: real-time threads on " + realtime), lines.toString());
        assertTrue(lines.stream().noneMatch(line -> line.startsWith("cpu latency")), "no real-time dispatcher: "
                + lines);
        ThreadGrant dispatcher = scheduler.platformReport().threads().getFirst();
        assertEquals(io.etherware.rt.platform.CpuSet.of(java.util.Arrays.copyOf(allowed, allowed.length - 1)),
                dispatcher.grantedCpus(), "an ordinary dispatcher on the ordinary CPUs");

        scheduler.shutdown(TimeUnit.SECONDS.toNanos(1));
        assertTrue(Platform.current().cpuPartition().isEmpty(), "the scheduler's share of the partition is released");
        assertTrue(java.util.Arrays.equals(allowed, io.etherware.rt.platform.internal.LinuxNative.getAffinity(0)),
                "and this thread may use every CPU it had");
    }

    @Test
    void shouldRunEveryPooledJobOfManySubmittersExactlyOnceAndReuseTheJobs() throws Exception {
        int submitters = 4;
        int perSubmitter = 20_000;
        int window = 256;
        long deadlineNs = System.nanoTime() + TimeUnit.SECONDS.toNanos(60); // every loop here ends by then
        var runs = new java.util.concurrent.atomic.AtomicIntegerArray(submitters * perSubmitter);
        var handled = new java.util.concurrent.atomic.AtomicLongArray(submitters);
        java.util.Set<Job> seen = ConcurrentHashMap.newKeySet();
        // Every 7th job is parked the first time, as the kernel parks a job whose component is
        // busy, and submitted again later: it must not be recycled meanwhile.
        record Parked(Job job, long sequence) {
        }
        var parked = new LinkedBlockingQueue<Parked>();
        java.util.Set<Long> parkedOnce = ConcurrentHashMap.newKeySet();
        var changedWhileParked = new java.util.concurrent.atomic.AtomicInteger();
        var twoDispatchers = rule("by-parity", 2, QueuePolicy.EARLIEST_DEADLINE_FIRST,
                job -> new Placement((int) (job.sequence() & 1), job.sequence()));
        start(RealtimeSchedulerConfig.builder().threadSchedulingRule(ThreadSchedulingRule.nonRealtime(2))
                .placementRule(twoDispatchers).build(), (job, nowNs) -> {
                    if (job.sequence() % 7 == 0 && parkedOnce.add(job.sequence())) {
                        parked.add(new Parked(job, job.sequence()));
                        return false;
                    }
                    seen.add(job);
                    int index = (int) job.sequence();
                    runs.incrementAndGet(index);
                    handled.incrementAndGet(index / perSubmitter);
                    return true;
                }, NodeClock.system());
        Thread resubmitter = Thread.ofPlatform().start(() -> {
            while (System.nanoTime() < deadlineNs) {
                Parked next;
                try {
                    next = parked.poll(10, TimeUnit.MILLISECONDS);
                } catch (InterruptedException e) {
                    return;
                }
                if (next != null) {
                    if (next.job().sequence() != next.sequence() || next.job().message() == null) {
                        changedWhileParked.incrementAndGet(); // recycled and reused while parked
                    }
                    scheduler.submit(next.job());
                }
            }
        });
        var message = TestJobs.job("sink", Criticality.HIGH, 0, 0).message();
        var threads = new ArrayList<Thread>();
        var refused = new java.util.concurrent.atomic.AtomicInteger();
        for (int s = 0; s < submitters; s++) {
            int submitter = s;
            threads.add(Thread.ofPlatform().start(() -> {
                for (int i = 0; i < perSubmitter && System.nanoTime() < deadlineNs; i++) {
                    // At most a window of jobs out per submitter.
                    while (i - handled.get(submitter) >= window && System.nanoTime() < deadlineNs) {
                        java.util.concurrent.locks.LockSupport.parkNanos(50_000);
                    }
                    long sequence = (long) submitter * perSubmitter + i;
                    if (!scheduler.submit(Job.pooled(message, "sink", "sink", sequence, 0L))) {
                        refused.incrementAndGet();
                    }
                }
            }));
        }
        for (Thread thread : threads) {
            thread.join(TimeUnit.SECONDS.toMillis(70));
        }
        while (scheduler.stats().jobsRun() < (long) submitters * perSubmitter && System.nanoTime() < deadlineNs) {
            Thread.sleep(1);
        }
        resubmitter.interrupt();
        resubmitter.join();
        assertEquals(0, refused.get());
        assertEquals(0, changedWhileParked.get(), "a parked job was recycled and reused before it ran");
        assertTrue(parkedOnce.size() > 10_000, parkedOnce.size() + " jobs parked and submitted again");
        for (int i = 0; i < runs.length(); i++) {
            assertEquals(1, runs.get(i), "job " + i + " ran " + runs.get(i) + " times");
        }
        assertTrue(seen.size() <= submitters * 2 * 1024, seen.size() + " distinct jobs for "
                + submitters * perSubmitter + " deliveries: the dispatchers' recycled jobs were reused");
    }

    @Test
    void shouldRunQueuedJobsByKeyThenArrivalWhenTheDispatcherWasBusy() throws Exception {
        var keys = new ConcurrentHashMap<Long, Long>();
        var blockerRunning = new CountDownLatch(1);
        var release = new CountDownLatch(1);
        var order = new CopyOnWriteArrayList<Long>();
        var allDone = new CountDownLatch(6);
        start(oneDispatcher(keyTable(keys)).build(), (job, nowNs) -> {
            if (job.targetName().equals("blocker")) {
                blockerRunning.countDown();
                await(release);
            } else {
                order.add(job.sequence());
            }
            allDone.countDown();
            return true;
        }, NodeClock.system());

        scheduler.submit(job("blocker", QoS.NONE, 0));
        assertTrue(blockerRunning.await(5, TimeUnit.SECONDS));
        long[] keyOfEach = {30, 10, 20, 10, 30};
        var jobs = new ArrayList<Job>();
        for (long key : keyOfEach) {
            Job job = job("worker", QoS.NONE, 0);
            keys.put(job.sequence(), key);
            jobs.add(job);
        }
        jobs.forEach(scheduler::submit);
        release.countDown();
        assertTrue(allDone.await(5, TimeUnit.SECONDS));

        List<Long> expected = List.of(jobs.get(1).sequence(), jobs.get(3).sequence(), jobs.get(2).sequence(),
                jobs.get(0).sequence(), jobs.get(4).sequence());
        assertEquals(expected, order);
    }

    @Test
    void shouldKeepThePlacementWhenAParkedJobIsSubmittedAgain() throws Exception {
        var clock = new ManualClock(CLOCK_START_NS);
        var ran = new LinkedBlockingQueue<Job>();
        var parkedOnce = ConcurrentHashMap.<Long>newKeySet();
        start(RealtimeSchedulerConfig.builder().threadSchedulingRule(ThreadSchedulingRule.tableII().withoutRealtime())
                .build(), (job, nowNs) -> {
                    if (parkedOnce.add(job.sequence())) {
                        return false;
                    }
                    ran.add(job);
                    return true;
                }, clock);

        Job job = job("a", Criticality.MIDDLE, 15 * MS, clock.nanoTime());
        long placedAtNs = clock.nanoTime();
        scheduler.submit(job);
        awaitParked(2, 1);
        clock.advance(500 * MS);
        job.reserve();
        scheduler.submit(job);

        Job back = ran.poll(5, TimeUnit.SECONDS);
        assertEquals(job, back);
        assertEquals(2, back.dispatcherId());
        assertEquals(placedAtNs + 15 * MS, back.key(), "the key of the first placement, not a new one");
        assertEquals(1, scheduler.stats().dispatcher(2).jobsParked());
        awaitRun(2, 1); // counted after the runner returns, which may be after the poll above
    }

    @Test
    void shouldCountExactlyOneDeadlineMissWhenOneJobOverruns() throws Exception {
        var clock = new ManualClock(CLOCK_START_NS);
        var misses = new CopyOnWriteArrayList<DeadlineMiss>();
        var done = new LinkedBlockingQueue<Job>();
        Map<String, Long> executionNs = Map.of("late", 6 * MS, "just-in-time", 5 * MS, "no-deadline", 100 * MS);
        start(oneDispatcher(new FifoPlacement()).deadlineMissHandler(misses::add).build(), (job, nowNs) -> {
            clock.advance(executionNs.get(job.targetName()));
            done.add(job);
            return true;
        }, clock);

        var withDeadline = QoS.of(Criticality.HIGH).withDeadlineNs(5 * MS);
        for (String target : List.of("late", "just-in-time", "no-deadline")) {
            QoS qos = target.equals("no-deadline") ? QoS.of(Criticality.LOW) : withDeadline;
            scheduler.submit(job(target, qos, clock.nanoTime()));
            // One at a time, so each starts the moment it is released.
            assertTrue(done.poll(5, TimeUnit.SECONDS) != null);
        }

        awaitRun(0, 3);
        assertEquals(1, scheduler.stats().deadlineMisses());
        assertEquals(1, scheduler.stats().dispatcher(0).deadlineMisses());
        assertEquals(1, misses.size());
        assertEquals("late", misses.getFirst().component());
        assertEquals(1 * MS, misses.getFirst().latenessNs());
        assertEquals(1, scheduler.stats().component("late").orElseThrow().deadlineMisses());
        assertEquals(0, scheduler.stats().component("just-in-time").orElseThrow().deadlineMisses());
        assertEquals(0, scheduler.stats().component("no-deadline").orElseThrow().deadlineMisses());
        assertEquals(100 * MS, scheduler.stats().component("no-deadline").orElseThrow().maxExecutionNs());
        var execution = scheduler.stats().dispatcher(0).executionNs();
        assertEquals(3, execution.count());
        assertEquals(100 * MS, execution.maxNs(), MS, "max within the 2 significant digits: " + execution);
        assertEquals(0, scheduler.stats().dispatcher(0).startLatencyNs().maxNs());
    }

    @Test
    void shouldNotCountAParkedJobAsRun() throws Exception {
        start(oneDispatcher(new FifoPlacement()).build(), (job, nowNs) -> false, NodeClock.system());
        scheduler.submit(job("busy", Criticality.HIGH, 0, System.nanoTime()));
        awaitParked(0, 1);
        DispatcherStats stats = scheduler.stats().dispatcher(0);
        assertEquals(0, stats.jobsRun());
        assertEquals(0, stats.startLatencyNs().count());
        assertTrue(scheduler.stats().components().isEmpty());
    }

    @Test
    void shouldReturnQueuedJobsAndRefuseNewOnesWhenShutdownTimesOut() throws Exception {
        var running = new CountDownLatch(1);
        var interrupted = new CountDownLatch(1);
        start(oneDispatcher(new FifoPlacement()).build(), (job, nowNs) -> {
            if (job.targetName().equals("stuck")) {
                running.countDown();
                try {
                    new CountDownLatch(1).await();
                } catch (InterruptedException e) {
                    interrupted.countDown();
                }
            }
            return true;
        }, NodeClock.system());
        scheduler.submit(job("stuck", QoS.NONE, 0));
        assertTrue(running.await(5, TimeUnit.SECONDS));
        var queued = List.of(job("q", QoS.NONE, 0), job("q", QoS.NONE, 0), job("q", QoS.NONE, 0));
        queued.forEach(scheduler::submit);

        List<Job> notRun = scheduler.shutdown(50 * MS);

        assertTrue(interrupted.await(5, TimeUnit.SECONDS), "the stuck job was interrupted");
        assertEquals(new java.util.HashSet<>(queued), new java.util.HashSet<>(notRun));
        assertFalse(scheduler.submit(job("late", QoS.NONE, 0)));
    }

    @Test
    void shouldRunReservedJobsButRefuseNewOnesWhileDraining() throws Exception {
        var blockerRunning = new CountDownLatch(1);
        var release = new CountDownLatch(1);
        var ran = Collections.synchronizedList(new ArrayList<Job>());
        start(oneDispatcher(new FifoPlacement()).build(), (job, nowNs) -> {
            if (job.targetName().equals("blocker")) {
                blockerRunning.countDown();
                await(release);
            }
            ran.add(job);
            return true;
        }, NodeClock.system());
        scheduler.submit(job("blocker", QoS.NONE, 0));
        assertTrue(blockerRunning.await(5, TimeUnit.SECONDS));
        var shutdown = new java.util.concurrent.CompletableFuture<List<Job>>();
        Thread.ofPlatform().start(() -> shutdown.complete(scheduler.shutdown(TimeUnit.SECONDS.toNanos(10))));
        int acceptedProbes = 0;
        while (scheduler.submit(job("probe", QoS.NONE, 0))) {
            acceptedProbes++;
            Thread.sleep(1);
        }
        Job reserved = job("reserved", QoS.NONE, 0);
        reserved.reserve();

        assertTrue(scheduler.submit(reserved));
        release.countDown();

        assertEquals(List.of(), shutdown.get(10, TimeUnit.SECONDS));
        assertTrue(ran.contains(reserved));
        assertEquals(2 + acceptedProbes, ran.size(), "blocker, accepted probes and the reserved job ran");
    }

    @Test
    void shouldThrowWhenSubmittedBeforeStart() {
        var notStarted = RealtimeScheduler.withDefaults();
        var error = assertThrows(IllegalStateException.class, () -> notStarted.submit(job("a", QoS.NONE, 0)));
        assertTrue(error.getMessage().contains("not started"), error.getMessage());
    }

    @Test
    void shouldOrderByDispatcherPriorityThenKeyThenArrivalForUrgency() {
        var urgency = RealtimeScheduler.withDefaults().urgency();
        Job low = placed(3, 1);
        Job high = placed(1, 100);
        Job middle = placed(2, 50);
        Job none = placed(0, 0);
        Job highEarlier = placed(1, 10);
        Job highSameKeyLater = placed(1, 10);
        var jobs = new ArrayList<>(List.of(none, low, middle, highSameKeyLater, high, highEarlier));
        jobs.sort(urgency);
        assertEquals(List.of(highEarlier, highSameKeyLater, high, middle, low, none), jobs);
    }

    private static Job placed(int dispatcherId, long key) {
        Job job = job("a", QoS.NONE, 0);
        job.place(dispatcherId, key);
        return job;
    }

    @Test
    void shouldRunOnDispatcherZeroWhenTheRuleNamesADispatcherThatDoesNotExist() throws Exception {
        var ran = new LinkedBlockingQueue<Job>();
        var broken = rule("broken", 1, QueuePolicy.FIFO, job -> new Placement(7, 0));
        start(RealtimeSchedulerConfig.builder().threadSchedulingRule(ThreadSchedulingRule.nonRealtime(2))
                .placementRule(broken).build(), (job, nowNs) -> ran.add(job), NodeClock.system());
        assertTrue(scheduler.submit(job("a", QoS.NONE, 0)));
        assertEquals(0, ran.poll(5, TimeUnit.SECONDS).dispatcherId());
    }

    @Test
    void shouldReportOneLinePerDispatcherWhenStarted() {
        start(RealtimeSchedulerConfig.builder().threadSchedulingRule(ThreadSchedulingRule.tableII().withoutRealtime())
                .build(), (job, nowNs) -> true, NodeClock.system());
        var lines = scheduler.platformReport().lines();
        assertEquals(4, lines.size(), String.join("\n", lines));
        assertTrue(lines.get(2).startsWith("rt-dispatcher-2 tid="), lines.get(2));
        assertTrue(lines.get(2).contains("requested SCHED_OTHER"), lines.get(2));
    }

    @Test
    void shouldRunDispatchersAtTableIIPrioritiesAsProcShowsWhenPrivilegedElseReportTheRefusal() {
        start(RealtimeSchedulerConfig.defaults(), (job, nowNs) -> true, NodeClock.system());
        var threads = scheduler.platformReport().threads();
        boolean privileged = Platform.current().isAvailable() && OsThreadStat.hasCapSysNice();
        int[] expected = {0, 80, 70, 60};
        for (int id = 0; id < 4; id++) {
            ThreadGrant grant = threads.get(id);
            if (privileged) {
                // /proc is read independently of the FFM calls the scheduler made.
                OsThreadStat proc = OsThreadStat.of(grant.osThreadId());
                assertEquals(expected[id], proc.rtPriority(), grant.toLine());
                assertEquals(id == 0 ? 0 : 1, proc.policy(), grant.toLine());
            } else if (id > 0) {
                assertEquals(ThreadPolicy.NON_REALTIME, grant.granted(), grant.toLine());
                assertFalse(grant.refusals().isEmpty(), grant.toLine());
            }
        }
    }

    @Test
    void shouldWriteDispatchAndDeadlineMissEventsWhenFlightRecorderIsOn(@TempDir Path dir) throws Exception {
        var clock = new ManualClock(CLOCK_START_NS);
        var done = new LinkedBlockingQueue<Job>();
        start(oneDispatcher(new FifoPlacement()).build(), (job, nowNs) -> {
            clock.advance(job.targetName().equals("late") ? 10 * MS : 0);
            done.add(job);
            return true;
        }, clock);
        Path file = dir.resolve("schedule.jfr");
        try (var recording = new Recording()) {
            recording.enable("io.etherware.rt.Dispatch");
            recording.enable("io.etherware.rt.DeadlineMiss");
            recording.start();
            scheduler.submit(job("on-time", QoS.of(Criticality.HIGH), clock.nanoTime()));
            scheduler.submit(job("late", QoS.of(Criticality.HIGH).withDeadlineNs(2 * MS), clock.nanoTime()));
            done.poll(5, TimeUnit.SECONDS);
            done.poll(5, TimeUnit.SECONDS);
            awaitRun(0, 2);
            recording.stop();
            recording.dump(file);
        }
        List<RecordedEvent> events = RecordingFile.readAllEvents(file);
        long dispatches = events.stream().filter(e -> e.getEventType().getName().equals("io.etherware.rt.Dispatch"))
                .count();
        var missEvents = events.stream()
                .filter(e -> e.getEventType().getName().equals("io.etherware.rt.DeadlineMiss")).toList();
        assertEquals(2, dispatches);
        assertEquals(1, missEvents.size());
        assertEquals("late", missEvents.getFirst().getString("component"));
        assertEquals(8 * MS, missEvents.getFirst().getDuration("lateness").toNanos());
        assertTrue(Files.size(file) > 0);
    }

    private void awaitParked(int dispatcherId, long count) throws InterruptedException {
        long deadline = System.nanoTime() + TimeUnit.SECONDS.toNanos(5);
        while (scheduler.stats().dispatcher(dispatcherId).jobsParked() < count && System.nanoTime() < deadline) {
            Thread.sleep(1);
        }
        assertEquals(count, scheduler.stats().dispatcher(dispatcherId).jobsParked());
    }

    private void awaitRun(int dispatcherId, long count) throws InterruptedException {
        long deadline = System.nanoTime() + TimeUnit.SECONDS.toNanos(5);
        while (scheduler.stats().dispatcher(dispatcherId).jobsRun() < count && System.nanoTime() < deadline) {
            Thread.sleep(1);
        }
        assertEquals(count, scheduler.stats().dispatcher(dispatcherId).jobsRun());
    }

    private static void await(CountDownLatch latch) {
        try {
            latch.await();
        } catch (InterruptedException e) {
            Thread.currentThread().interrupt();
        }
    }
}
