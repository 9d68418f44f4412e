package io.etherware.services.network;

import static org.junit.jupiter.api.Assertions.assertEquals;
import static org.junit.jupiter.api.Assertions.assertTrue;
import static org.junit.jupiter.api.Assumptions.assumeTrue;

import io.etherware.core.time.NodeClock;
import io.etherware.core.message.Criticality;
import io.etherware.core.message.Profile;
import io.etherware.core.message.QoS;
import io.etherware.core.message.Text;
import io.etherware.rt.platform.CpuSet;
import io.etherware.rt.platform.Platform;
import io.etherware.rt.platform.ThreadGrant;
import io.etherware.rt.platform.ThreadPolicy;
import io.etherware.rt.scheduling.CriticalityDeadlinePlacement;
import io.etherware.rt.scheduling.RealtimeScheduler;
import io.etherware.rt.scheduling.RealtimeSchedulerConfig;
import io.etherware.rt.scheduling.ThreadSchedulingRule;
import java.time.Duration;
import java.util.ArrayList;
import java.util.List;
import java.util.concurrent.CompletableFuture;
import java.util.concurrent.TimeUnit;
import java.util.concurrent.atomic.AtomicInteger;
import java.util.concurrent.locks.LockSupport;
import org.junit.jupiter.api.Test;

/**
 * A HIGH loop across the network keeps its priority on the receiving node: node A asks a sensor
 * on node B every 10 ms (HIGH, deadline 8 ms) while B's LOW dispatcher, at its real-time priority,
 * works on the same CPU as B's HIGH dispatcher and B's network threads. The network threads run
 * above the dispatchers (the node's priority map), so LOW work never holds up the threads that
 * carry the HIGH requests and their replies. LOW work burns at most 1 ms at a time and rests as
 * long (no real-time thread keeps a CPU), bounded to the test's few seconds.
 *
 * <p>Node A is real-time too (its network threads above its dispatchers, the requesting thread at
 * the HIGH priority), as a deployment's nodes are: the round trips then measure B's claim, not how
 * long A's ordinary threads wait behind whatever else the machine runs.
 */
class RemoteHighUnderLowIT {

    private static final Profile SENSOR = Profile.of("sensor");
    private static final Profile BACKGROUND = Profile.of("background");
    private static final long PERIOD_NS = TimeUnit.MILLISECONDS.toNanos(10);
    private static final long DEADLINE_NS = TimeUnit.MILLISECONDS.toNanos(8);
    private static final int REQUESTS = 200;
    private static final long LOW_JOB_NS = TimeUnit.MILLISECONDS.toNanos(100);

    @Test
    void shouldAnswerEveryRemoteHighRequestWithinItsDeadlineWhileLowWorkRunsAtItsRealtimePriority()
            throws Exception {
        int cpu = Runtime.getRuntime().availableProcessors() - 1;
        var scheduler = new RealtimeScheduler(RealtimeSchedulerConfig.builder().name("b-one-cpu")
                .threadSchedulingRule(tableIIOnOneCpu(cpu)).build());
        var lowHandled = new AtomicInteger();
        try (var b = TestNode.start("b", NodeClock.system(), TestNode.config().threadCpus(CpuSet.of(cpu)), settings -> settings
                     .scheduler(() -> scheduler));
             var a = TestNode.start("a", NodeClock.system(), TestNode.config().peer(b.address()),
                     settings -> settings.scheduler(RealtimeScheduler::withDefaults))) {
            ThreadGrant high = scheduler.platformReport().threads().get(CriticalityDeadlinePlacement.HIGH_DISPATCHER);
            String refused = "the claim needs SCHED_FIFO: " + high.toLine();
            if ("true".equals(System.getenv("CI"))) {
                assertTrue(high.granted().isRealtime(), refused);
            }
            assumeTrue(high.granted().isRealtime(), refused);
            assertEquals(ThreadPolicy.fifo(ThreadSchedulingRule.HIGH_PRIORITY + 1), b.net.ioThreadPolicy(),
                    "B's lane 0 (HIGH, MIDDLE) threads sit above its HIGH dispatcher");
            assertEquals(ThreadPolicy.fifo(ThreadSchedulingRule.LOW_PRIORITY + 1), b.net.ioThreadPolicy(1),
                    "B's lane 1 (LOW, NONE) threads sit just above its LOW dispatcher, below MIDDLE and HIGH");
            assertEquals(ThreadPolicy.fifo(ThreadSchedulingRule.HIGH_PRIORITY + 1), a.net.ioThreadPolicy(),
                    "A's lane 0 threads sit above its HIGH dispatcher too");

            b.node.add(SENSOR, () -> (message, context) -> context.reply(message, new Text("21.5")));
            b.node.add(BACKGROUND, () -> (message, context) -> {
                occupyHalfBusy(LOW_JOB_NS);
                lowHandled.incrementAndGet();
            });
            assertTrue(a.net.awaitResolvable(SENSOR, Duration.ofSeconds(30)));
            // Warm up the path, then keep B's LOW dispatcher busy for the whole loop.
            for (int i = 0; i < 20; i++) {
                a.node.requestBlocking(SENSOR, new Text("warm-up"));
            }
            int lowJobs = (int) (REQUESTS * PERIOD_NS / LOW_JOB_NS) + 5;
            for (int i = 0; i < lowJobs; i++) {
                b.node.send(BACKGROUND, new Text("work"), QoS.of(Criticality.LOW));
            }

            QoS highQos = QoS.of(Criticality.HIGH).withDeadlineNs(DEADLINE_NS);
            List<CompletableFuture<Long>> roundTrips = new ArrayList<>();
            // The requester is A's HIGH loop: it runs at the HIGH dispatcher's priority and only sleeps.
            Platform.current().configureCurrentThread(ThreadPolicy.fifo(ThreadSchedulingRule.HIGH_PRIORITY),
                    CpuSet.inherit());
            try {
                long nextNs = System.nanoTime();
                for (int i = 0; i < REQUESTS; i++) {
                    long sentNs = System.nanoTime();
                    roundTrips.add(a.node.request(SENSOR, new Text("read"), highQos, TimeUnit.SECONDS.toNanos(5))
                            .thenApply(reply -> System.nanoTime() - sentNs));
                    nextNs += PERIOD_NS;
                    LockSupport.parkNanos(nextNs - System.nanoTime());
                }
            } finally {
                Platform.current().configureCurrentThread(ThreadPolicy.NON_REALTIME, CpuSet.inherit());
            }
            int withinDeadline = 0;
            long worstNs = 0;
            for (CompletableFuture<Long> each : roundTrips) {
                long roundTripNs = each.get(30, TimeUnit.SECONDS); // every request answered: nothing lost
                worstNs = Math.max(worstNs, roundTripNs);
                if (roundTripNs <= DEADLINE_NS) {
                    withinDeadline++;
                }
            }
            int lowDuringLoop = lowHandled.get();
            String summary = withinDeadline + " of " + REQUESTS + " HIGH round trips within "
                    + DEADLINE_NS / 1_000_000 + " ms, worst " + worstNs / 1000 + " us; LOW jobs done meanwhile: "
                    + lowDuringLoop + " of " + lowJobs;
            System.out.println("RemoteHighUnderLowIT: " + summary);
            assertTrue(lowDuringLoop < lowJobs, "LOW work was still queued at the end: the loop ran under it: "
                    + summary);
            // A stock JVM's safepoints can hold a real-time thread now and then on a loaded
            // 2-core machine (see NodePriorityIsolationIT): all answered, 95 % within the deadline.
            assertTrue(withinDeadline >= REQUESTS * 95 / 100, summary);
        }
    }

    private static ThreadSchedulingRule tableIIOnOneCpu(int cpu) {
        return ThreadSchedulingRule.tableII().withRealtimeOn(CpuSet.of(cpu));
    }

    /** Holds the CPU for {@code durationNs}, burning 1 ms and resting 1 ms in turn. */
    private static void occupyHalfBusy(long durationNs) {
        long endNs = System.nanoTime() + durationNs;
        long value = 0;
        while (System.nanoTime() < endNs) {
            long burnUntilNs = Math.min(endNs, System.nanoTime() + 1_000_000);
            while (System.nanoTime() < burnUntilNs) {
                value += value ^ burnUntilNs;
            }
            LockSupport.parkNanos(Math.min(1_000_000, Math.max(0, endNs - System.nanoTime())));
        }
        if (value == 42) {
            System.out.print("");
        }
    }
}
