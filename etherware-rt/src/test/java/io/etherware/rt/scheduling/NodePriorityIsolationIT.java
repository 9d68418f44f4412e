package io.etherware.rt.scheduling;

import static org.junit.jupiter.api.Assertions.assertEquals;
import static org.junit.jupiter.api.Assertions.assertTrue;
import static org.junit.jupiter.api.Assumptions.assumeTrue;

import io.etherware.core.kernel.EtherwareNode;
import io.etherware.core.kernel.NodeStats;
import io.etherware.core.message.Contents;
import io.etherware.core.message.Criticality;
import io.etherware.core.message.Profile;
import io.etherware.core.message.QoS;
import io.etherware.core.scheduler.FifoScheduler;
import io.etherware.core.scheduler.Scheduler;
import io.etherware.core.time.NodeClock;
import io.etherware.rt.platform.CpuSet;
import io.etherware.rt.platform.ThreadGrant;
import java.util.ArrayList;
import java.util.List;
import java.util.concurrent.ConcurrentLinkedQueue;
import java.util.concurrent.CountDownLatch;
import java.util.concurrent.TimeUnit;
import java.util.concurrent.atomic.AtomicLong;
import java.util.concurrent.atomic.AtomicReference;
import java.util.function.Supplier;
import org.junit.jupiter.api.Test;

/**
 * The paper's core claim on a real {@link EtherwareNode}: a LOW job keeps component B and its
 * dispatcher busy for 1 s while component A receives a HIGH message every 15 ms. With the
 * real-time scheduler (Table II, Algorithm 1) every HIGH message starts within one period of its
 * release, while the LOW job is still running (what exactly is asserted:
 * {@link #assertRunsDuringTheLowJob}); with the kernel's {@link FifoScheduler} in the same test,
 * none of the HIGH messages starts during the LOW job, and those sent during it wait for its end. Both sides are asserted, so the test fails if either is wrong. B meanwhile keeps
 * working: every LOW message sent to it is handled, none lost.
 *
 * <p>The LOW job is {@link Burners#occupyHalfBusy}: it holds B and the LOW dispatcher (SCHED_FIFO
 * 60) for the whole second and burns CPU half of it, so the HIGH dispatcher really has to preempt
 * it when they share a CPU, without a real-time thread ever keeping a CPU for more than 2 ms.
 * CPU saturation comes from ordinary (SCHED_OTHER) threads, one per core, bounded in time. The
 * messages come from a {@link PeriodicSender}: a HIGH one to A every period, a short LOW one to B
 * every fifth.
 */
class NodePriorityIsolationIT {

    private static final Profile A = Profile.of("a");
    private static final Profile B = Profile.of("b");
    private static final long PERIOD_NS = TimeUnit.MILLISECONDS.toNanos(15);
    private static final long LOW_JOB_NS = TimeUnit.SECONDS.toNanos(1);
    /** 60 periods of 15 ms: 0.9 s, all sent while the 1 s LOW job runs (if the sender is on time). */
    private static final int HIGH_MESSAGES = 60;
    /** One short LOW message to B every 5th period, queued behind the long one. */
    private static final int LOW_EVERY = 5;
    private static final int SHORT_LOW_MESSAGES = HIGH_MESSAGES / LOW_EVERY;
    private static final long BURN_MAX_MS = 6_000;

    record Ping(long sentNs, int sequence) implements Contents {
    }

    record Work(long busyNs) implements Contents {
    }

    /** One HIGH message: when it was sent and when A's handler started it (node clock). */
    record Sample(long sentNs, long startNs) {
        long latencyNs() {
            return startNs - sentNs;
        }
    }

    /** What one run of the scenario saw. */
    record Outcome(String scheduler, List<Sample> high, long lowStartNs, long lowEndNs, long lowHandled,
                   NodeStats stats) {

        /** The HIGH messages sent while the LOW job ran. */
        long sentDuringLowJob() {
            return high.stream().filter(s -> s.sentNs() > lowStartNs && s.sentNs() < lowEndNs).count();
        }

        /** The HIGH messages whose handling started while the LOW job ran. */
        long startedDuringLowJob() {
            return high.stream().filter(s -> s.startNs() > lowStartNs && s.startNs() < lowEndNs).count();
        }

        long maxLatencyNs() {
            return high.stream().mapToLong(Sample::latencyNs).max().orElseThrow();
        }

        String summary() {
            return scheduler + ": " + high.size() + " HIGH, " + sentDuringLowJob() + " sent and "
                    + startedDuringLowJob() + " started during the LOW job, max send-to-start "
                    + maxLatencyNs() / 1000 + " us";
        }
    }

    @Test
    void shouldStartHighMessagesWithinOnePeriodWhileALowJobKeepsAnotherComponentBusy() throws Exception {
        var realtime = new AtomicReference<RealtimeScheduler>();
        Outcome rt = run("rt", () -> recorded(realtime, RealtimeScheduler.withDefaults()), false);
        Outcome fifo = run("fifo", FifoScheduler::new, false);

        assertRunsDuringTheLowJob(rt, realtime.get());
        assertWaitsBehindTheLowJob(fifo);
        assertNothingLost(rt);
        assertNothingLost(fifo);
    }

    @Test
    void shouldStartHighMessagesWithinOnePeriodWhenOrdinaryThreadsSaturateEveryCore() throws Exception {
        var realtime = new AtomicReference<RealtimeScheduler>();
        Outcome rt = run("rt", () -> recorded(realtime, RealtimeScheduler.withDefaults()), true);
        ThreadGrant high = realtime.get().platformReport().threads().get(CriticalityDeadlinePlacement.HIGH_DISPATCHER);
        String refused = "under saturation the claim needs SCHED_FIFO: " + high.toLine();
        // A refusal skips on a developer's laptop and fails in CI (CI=true), where root is expected.
        if ("true".equals(System.getenv("CI"))) {
            assertTrue(high.granted().isRealtime(), refused);
        }
        assumeTrue(high.granted().isRealtime(), refused);
        // The same rule with the three real-time dispatchers on one CPU: HIGH must preempt the LOW
        // dispatcher there rather than run beside it on the other core.
        int cpu = Runtime.getRuntime().availableProcessors() - 1;
        var pinned = new AtomicReference<RealtimeScheduler>();
        Outcome rtOneCpu = run("rt-one-cpu", () -> recorded(pinned, new RealtimeScheduler(RealtimeSchedulerConfig.builder()
                .name("rt-one-cpu").threadSchedulingRule(tableIIOnOneCpu(cpu)).build())), true);
        Outcome fifo = run("fifo", FifoScheduler::new, true);

        assertRunsDuringTheLowJob(rt, realtime.get());
        assertRunsDuringTheLowJob(rtOneCpu, pinned.get());
        List<ThreadGrant> oneCpu = pinned.get().platformReport().threads();
        assertEquals(CpuSet.of(cpu), oneCpu.get(CriticalityDeadlinePlacement.HIGH_DISPATCHER).grantedCpus());
        assertEquals(CpuSet.of(cpu), oneCpu.get(CriticalityDeadlinePlacement.LOW_DISPATCHER).grantedCpus());
        assertWaitsBehindTheLowJob(fifo);
        assertNothingLost(rt);
        assertNothingLost(rtOneCpu);
        assertNothingLost(fifo);
    }

    /**
     * HIGH jobs start within one period of their release, as the scheduler measured it (the
     * kernel releases a job when it queues it): 95 % of them, and every one within a tenth of the
     * LOW job that the baseline waits for entirely. From {@code send} to {@code onMessage}, measured
     * here, 90 % are within one period and all within a tenth of the LOW job: on the loaded
     * 2-vCPU development VM, about one saturated run in ten showed a real-time thread stalled for
     * 6-55 ms outside the scheduler's release-to-start window, with no GC in the run. Most likely
     * waits inside the JVM or the OS (allocation, page faults) behind preempted ordinary threads,
     * which is what {@code lockMemory(true)} and a pre-touched heap are for.
     */
    private static void assertRunsDuringTheLowJob(Outcome outcome, RealtimeScheduler scheduler) {
        assertEquals(HIGH_MESSAGES, outcome.high().size(), outcome.summary());
        DispatcherStats high = scheduler.stats().dispatcher(CriticalityDeadlinePlacement.HIGH_DISPATCHER);
        assertEquals(HIGH_MESSAGES, high.jobsRun(), outcome.summary());
        // Every job within a tenth of the LOW job (the baseline waits all of it), and nearly every
        // one within a period: a stock JVM's safepoints and the VM's own ordinary-priority threads
        // can hold a real-time thread for a period now and then on a loaded 2-core machine.
        long p95Ns = high.startLatencyNs().percentileNs(95);
        long maxNs = high.startLatencyNs().maxNs();
        assertTrue(p95Ns < PERIOD_NS && maxNs < LOW_JOB_NS / 10, outcome.summary() + "; the scheduler's release-to-start"
                + " p95 " + p95Ns / 1000 + " us, max " + maxNs / 1000 + " us");
        long withinPeriod = outcome.high().stream().filter(sample -> sample.latencyNs() < PERIOD_NS).count();
        assertTrue(withinPeriod >= HIGH_MESSAGES * 9 / 10, outcome.summary() + "; only " + withinPeriod
                + " within one period");
        assertTrue(outcome.maxLatencyNs() < LOW_JOB_NS / 10, outcome.summary());
        // Isolation, not luck: most of the HIGH stream ran while B's LOW job held its dispatcher.
        assertTrue(outcome.startedDuringLowJob() >= HIGH_MESSAGES / 2, outcome.summary());
    }

    private static void assertWaitsBehindTheLowJob(Outcome outcome) {
        assertEquals(HIGH_MESSAGES, outcome.high().size(), outcome.summary());
        assertTrue(outcome.sentDuringLowJob() >= HIGH_MESSAGES / 2, outcome.summary());
        assertEquals(0, outcome.startedDuringLowJob(), outcome.summary()
                + "; the baseline ran a HIGH message during the LOW job: is it one dispatcher?");
        assertTrue(outcome.maxLatencyNs() > LOW_JOB_NS / 2, outcome.summary());
    }

    private static void assertNothingLost(Outcome outcome) {
        assertEquals(1 + SHORT_LOW_MESSAGES, outcome.lowHandled(), outcome.scheduler() + ": LOW messages handled by B");
        NodeStats stats = outcome.stats();
        assertEquals(1 + SHORT_LOW_MESSAGES + HIGH_MESSAGES, stats.handled(), outcome.scheduler() + ": " + stats);
        assertEquals(0, stats.failed() + stats.undeliverable() + stats.discarded(), outcome.scheduler() + ": " + stats);
    }

    private static Outcome run(String name, Supplier<Scheduler> scheduler, boolean saturate) throws Exception {
        var high = new ConcurrentLinkedQueue<Sample>();
        var lowStartNs = new AtomicLong();
        var lowEndNs = new AtomicLong();
        var lowHandled = new AtomicLong();
        var lowStarted = new CountDownLatch(1);
        var highDone = new CountDownLatch(HIGH_MESSAGES);
        var lowDone = new CountDownLatch(1 + SHORT_LOW_MESSAGES);
        var node = EtherwareNode.builder().nodeId("isolation").scheduler(scheduler).build();
        try (node) {
            NodeClock clock = node.clock();
            node.add(A, () -> (message, context) -> {
                long startNs = clock.nanoTime();
                high.add(new Sample(message.contentsAs(Ping.class).sentNs(), startNs));
                highDone.countDown();
            });
            node.add(B, () -> (message, context) -> {
                long busyNs = message.contentsAs(Work.class).busyNs();
                if (busyNs > 0) {
                    lowStartNs.set(clock.nanoTime());
                    lowStarted.countDown();
                    Burners.occupyHalfBusy(busyNs);
                    lowEndNs.set(clock.nanoTime());
                }
                lowHandled.incrementAndGet();
                lowDone.countDown();
            });
            node.start();
            Burners burners = saturate ? Burners.start(Runtime.getRuntime().availableProcessors(), BURN_MAX_MS)
                    : Burners.none();
            try {
                node.send(B, new Work(LOW_JOB_NS), QoS.periodic(Criticality.LOW, 2 * LOW_JOB_NS));
                assertTrue(lowStarted.await(5, TimeUnit.SECONDS), "the LOW job did not start");
                PeriodicSender.run(HIGH_MESSAGES, PERIOD_NS, i -> {
                    node.send(A, new Ping(clock.nanoTime(), i), QoS.periodic(Criticality.HIGH, PERIOD_NS));
                    if (i % LOW_EVERY == LOW_EVERY - 1) {
                        node.send(B, new Work(0), QoS.periodic(Criticality.LOW, PERIOD_NS * LOW_EVERY));
                    }
                });
                assertTrue(highDone.await(10, TimeUnit.SECONDS), "HIGH messages did not all run");
                assertTrue(lowDone.await(10, TimeUnit.SECONDS), "LOW messages did not all run");
            } finally {
                burners.stop();
            }
        }
        // Read after close: the counters may lag the handlers by one message while running.
        var outcome = new Outcome(name, new ArrayList<>(high), lowStartNs.get(), lowEndNs.get(), lowHandled.get(),
                node.stats());
        System.out.println(outcome.summary() + (saturate ? ", saturated" : ""));
        return outcome;
    }

    private static RealtimeScheduler recorded(AtomicReference<RealtimeScheduler> holder, RealtimeScheduler scheduler) {
        holder.set(scheduler);
        return scheduler;
    }

    private static ThreadSchedulingRule tableIIOnOneCpu(int cpu) {
        return ThreadSchedulingRule.tableII().withRealtimeOn(CpuSet.of(cpu));
    }
}
