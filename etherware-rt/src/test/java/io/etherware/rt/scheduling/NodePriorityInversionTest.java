package io.etherware.rt.scheduling;

import static org.junit.jupiter.api.Assertions.assertEquals;
import static org.junit.jupiter.api.Assertions.assertTrue;

import io.etherware.core.kernel.EtherwareNode;
import io.etherware.core.message.Contents;
import io.etherware.core.message.Criticality;
import io.etherware.core.message.Profile;
import io.etherware.core.message.QoS;
import io.etherware.core.scheduler.FifoScheduler;
import io.etherware.core.scheduler.Scheduler;
import io.etherware.core.time.NodeClock;
import io.etherware.rt.platform.Platform;
import io.etherware.rt.platform.ThreadGrant;
import io.etherware.rt.platform.ThreadPolicy;
import java.util.List;
import java.util.concurrent.CopyOnWriteArrayList;
import java.util.concurrent.CountDownLatch;
import java.util.concurrent.TimeUnit;
import java.util.concurrent.atomic.AtomicLong;
import java.util.function.Supplier;
import org.junit.jupiter.api.Test;

/**
 * The priority inversion bound on a real {@link EtherwareNode}, for one component receiving two
 * criticalities (see {@link RealtimeScheduler}): a HIGH message sent while the component handles a
 * LOW one waits for the rest of that one handling and nothing else. It runs before the LOW
 * messages queued for the component earlier, and meanwhile the LOW dispatcher runs at the HIGH
 * dispatcher's priority (read back from the OS). The kernel's {@link FifoScheduler}, in the same
 * test, runs the HIGH message after all of them.
 */
class NodePriorityInversionTest {

    private static final Profile C = Profile.of("c");
    private static final long PERIOD_NS = TimeUnit.SECONDS.toNanos(1);
    /** How long the first LOW handler may hold the component if the test never lets it go. */
    private static final long LOW_WCET_MS = 2_000;
    /** Slack for a loaded machine between the LOW handler's end and the HIGH handler's start. */
    private static final long HAND_OVER_MARGIN_NS = TimeUnit.MILLISECONDS.toNanos(100);

    record Step(String name) implements Contents {
    }

    @Test
    void shouldRunHighRightAfterTheLowHandlingInProgressWhenOneComponentGetsBothCriticalities() throws Exception {
        var scheduler = RealtimeScheduler.withDefaults();
        var firstLowRunning = new CountDownLatch(1);
        var releaseFirstLow = new CountDownLatch(1);
        var order = new CopyOnWriteArrayList<String>();
        var firstLowEndNs = new AtomicLong();
        var highStartNs = new AtomicLong();
        var highSentNs = new AtomicLong();
        ThreadPolicy lowDispatcherWhileHighWaits;
        try (var node = node(() -> scheduler)) {
            var done = new CountDownLatch(4);
            addComponent(node, order, firstLowRunning, releaseFirstLow, firstLowEndNs, highStartNs, done);
            node.start();
            NodeClock clock = node.clock();
            send(node, "low-1", Criticality.LOW);
            assertTrue(firstLowRunning.await(5, TimeUnit.SECONDS), "low-1 did not start");
            send(node, "low-2", Criticality.LOW);
            send(node, "low-3", Criticality.LOW);
            highSentNs.set(clock.nanoTime());
            send(node, "high", Criticality.HIGH);
            awaitParked(scheduler, CriticalityDeadlinePlacement.HIGH_DISPATCHER);

            lowDispatcherWhileHighWaits = osPolicyOf(scheduler, CriticalityDeadlinePlacement.LOW_DISPATCHER);
            releaseFirstLow.countDown();
            assertTrue(done.await(5, TimeUnit.SECONDS), "handled only " + order);
            awaitOwnPolicy(scheduler, CriticalityDeadlinePlacement.LOW_DISPATCHER);
        }

        assertEquals(List.of("low-1", "high", "low-2", "low-3"), order,
                "HIGH runs right after the LOW handling in progress, before the LOW messages queued earlier");
        assertTrue(highStartNs.get() >= firstLowEndNs.get(), "one message at a time on the component");
        long highWaitNs = highStartNs.get() - highSentNs.get();
        long lowRestNs = firstLowEndNs.get() - highSentNs.get();
        assertTrue(highWaitNs <= lowRestNs + HAND_OVER_MARGIN_NS, "HIGH waited " + highWaitNs / 1000
                + " us, the LOW handling in progress had " + lowRestNs / 1000 + " us left");
        ThreadGrant high = scheduler.platformReport().threads().get(CriticalityDeadlinePlacement.HIGH_DISPATCHER);
        ThreadGrant low = scheduler.platformReport().threads().get(CriticalityDeadlinePlacement.LOW_DISPATCHER);
        DispatcherStats lowStats = scheduler.stats().dispatcher(CriticalityDeadlinePlacement.LOW_DISPATCHER);
        if (high.granted().isRealtime()) {
            assertEquals(high.granted(), lowDispatcherWhileHighWaits,
                    "the LOW dispatcher inherits the waiting HIGH message's priority, read back from the OS");
            assertEquals(1, lowStats.priorityBoosts());
        } else {
            assertEquals(low.granted(), lowDispatcherWhileHighWaits, "nothing to inherit without SCHED_FIFO");
            assertEquals(0, lowStats.priorityBoosts());
        }
    }

    @Test
    void shouldRunHighAfterEveryEarlierLowMessageWhenTheSchedulerIsTheFifoBaseline() throws Exception {
        var firstLowRunning = new CountDownLatch(1);
        var releaseFirstLow = new CountDownLatch(1);
        var order = new CopyOnWriteArrayList<String>();
        try (var node = node(FifoScheduler::new)) {
            var done = new CountDownLatch(4);
            addComponent(node, order, firstLowRunning, releaseFirstLow, new AtomicLong(), new AtomicLong(), done);
            node.start();
            send(node, "low-1", Criticality.LOW);
            assertTrue(firstLowRunning.await(5, TimeUnit.SECONDS), "low-1 did not start");
            send(node, "low-2", Criticality.LOW);
            send(node, "low-3", Criticality.LOW);
            send(node, "high", Criticality.HIGH);
            // send() has queued the jobs when it returns: nothing to wait for before the release.
            releaseFirstLow.countDown();
            assertTrue(done.await(5, TimeUnit.SECONDS), "handled only " + order);
        }

        assertEquals(List.of("low-1", "low-2", "low-3", "high"), order, "one FIFO queue: arrival order");
    }

    private static EtherwareNode node(Supplier<Scheduler> scheduler) {
        return EtherwareNode.builder().nodeId("inversion").scheduler(scheduler).build();
    }

    /**
     * Component C: records the order it handles messages in; the first LOW handler holds the
     * component until released (sleeping, bounded by {@link #LOW_WCET_MS}), standing for a LOW
     * handler that takes its whole WCET.
     */
    private static void addComponent(EtherwareNode node, List<String> order, CountDownLatch firstLowRunning,
                                     CountDownLatch releaseFirstLow, AtomicLong firstLowEndNs, AtomicLong highStartNs,
                                     CountDownLatch done) {
        NodeClock clock = node.clock();
        node.add(C, () -> (message, context) -> {
            long startNs = clock.nanoTime();
            String name = message.contentsAs(Step.class).name();
            order.add(name);
            if (name.equals("high")) {
                highStartNs.set(startNs);
            } else if (name.equals("low-1")) {
                firstLowRunning.countDown();
                releaseFirstLow.await(LOW_WCET_MS, TimeUnit.MILLISECONDS);
                firstLowEndNs.set(clock.nanoTime());
            }
            done.countDown();
        });
    }

    private static void send(EtherwareNode node, String name, Criticality criticality) {
        node.send(C, new Step(name), QoS.periodic(criticality, PERIOD_NS));
    }

    private static void awaitParked(RealtimeScheduler scheduler, int dispatcherId) throws InterruptedException {
        long deadlineNs = System.nanoTime() + TimeUnit.SECONDS.toNanos(5);
        while (scheduler.stats().dispatcher(dispatcherId).jobsParked() < 1 && System.nanoTime() < deadlineNs) {
            Thread.sleep(1);
        }
        assertEquals(1, scheduler.stats().dispatcher(dispatcherId).jobsParked(),
                "the HIGH message waits with the busy component");
    }

    private static ThreadPolicy osPolicyOf(RealtimeScheduler scheduler, int dispatcherId) {
        int tid = scheduler.platformReport().threads().get(dispatcherId).osThreadId();
        return Platform.current().threadPolicy(tid).orElse(ThreadPolicy.NON_REALTIME);
    }

    private static void awaitOwnPolicy(RealtimeScheduler scheduler, int dispatcherId) throws InterruptedException {
        ThreadPolicy own = scheduler.platformReport().threads().get(dispatcherId).granted();
        long deadlineNs = System.nanoTime() + TimeUnit.SECONDS.toNanos(5);
        while (!osPolicyOf(scheduler, dispatcherId).equals(own) && System.nanoTime() < deadlineNs) {
            Thread.sleep(1);
        }
        assertEquals(own, osPolicyOf(scheduler, dispatcherId), "back to its own priority after the LOW handling");
    }
}
