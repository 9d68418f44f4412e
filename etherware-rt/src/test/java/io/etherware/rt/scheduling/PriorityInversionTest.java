package io.etherware.rt.scheduling;

import static io.etherware.rt.scheduling.TestJobs.job;
import static org.junit.jupiter.api.Assertions.assertEquals;
import static org.junit.jupiter.api.Assertions.assertTrue;

import io.etherware.core.message.Criticality;
import io.etherware.core.message.QoS;
import io.etherware.core.scheduler.Job;
import io.etherware.core.time.NodeClock;
import io.etherware.rt.platform.Platform;
import io.etherware.rt.platform.ThreadGrant;
import io.etherware.rt.platform.ThreadPolicy;
import java.util.List;
import java.util.concurrent.CountDownLatch;
import java.util.concurrent.TimeUnit;
import org.junit.jupiter.api.AfterEach;
import org.junit.jupiter.api.Test;

/**
 * The priority inversion bound for one component receiving two criticalities (see
 * {@link RealtimeScheduler}): a HIGH message to a component busy with a LOW one waits for the rest
 * of that one LOW job (at most its WCET), then runs before the other LOW messages waiting for the
 * component; meanwhile the LOW job's dispatcher runs at the HIGH dispatcher's priority.
 */
class PriorityInversionTest {

    private static final long LOW_WCET_MS = 300;
    private static final long PERIOD_NS = TimeUnit.SECONDS.toNanos(1);
    private RealtimeScheduler scheduler;

    @AfterEach
    void stop() {
        scheduler.shutdown(TimeUnit.SECONDS.toNanos(2));
    }

    @Test
    void shouldRunHighNextAfterTheOneLowJobInProgressWhenBothTargetTheSameComponent() throws Exception {
        var highStartLatencyNs = new long[1];
        var firstLowRunning = new CountDownLatch(1);
        var releaseFirstLow = new CountDownLatch(1);
        var allDone = new CountDownLatch(4);
        var kernel = new FakeKernel().on("C", (job, startNs) -> {
            if (job.message().qos().criticality() == Criticality.HIGH) {
                highStartLatencyNs[0] = startNs - job.releaseNs();
            } else if (firstLowRunning.getCount() > 0) {
                firstLowRunning.countDown();
                // Stands for a LOW handler that takes its whole WCET; sleeping, not spinning.
                releaseFirstLow.await(LOW_WCET_MS, TimeUnit.MILLISECONDS);
            }
            allDone.countDown();
        });
        scheduler = RealtimeScheduler.withDefaults();
        kernel.bind(scheduler);
        scheduler.start(kernel, NodeClock.system());
        NodeClock clock = NodeClock.system();

        Job firstLow = job("C", QoS.periodic(Criticality.LOW, PERIOD_NS), clock.nanoTime());
        scheduler.submit(firstLow);
        assertTrue(firstLowRunning.await(5, TimeUnit.SECONDS));
        Job secondLow = job("C", QoS.periodic(Criticality.LOW, PERIOD_NS), clock.nanoTime());
        Job thirdLow = job("C", QoS.periodic(Criticality.LOW, PERIOD_NS), clock.nanoTime());
        scheduler.submit(secondLow);
        scheduler.submit(thirdLow);
        long highReleaseNs = clock.nanoTime();
        Job high = job("C", QoS.periodic(Criticality.HIGH, PERIOD_NS), highReleaseNs);
        scheduler.submit(high);
        awaitParked(CriticalityDeadlinePlacement.HIGH_DISPATCHER, 1);

        ThreadPolicy lowDispatcherWhileHighWaits = osPolicyOf(CriticalityDeadlinePlacement.LOW_DISPATCHER);
        releaseFirstLow.countDown();
        assertTrue(allDone.await(5, TimeUnit.SECONDS));

        assertEquals(List.of(firstLow, high, secondLow, thirdLow), kernel.ran(),
                "HIGH runs right after the LOW job in progress, before the LOW jobs that came earlier");
        assertTrue(highStartLatencyNs[0] <= TimeUnit.MILLISECONDS.toNanos(LOW_WCET_MS + 100),
                "HIGH waited " + highStartLatencyNs[0] / 1000 + " us, more than one LOW WCET plus margin");
        ThreadGrant lowGrant = scheduler.platformReport().threads().get(CriticalityDeadlinePlacement.LOW_DISPATCHER);
        ThreadGrant highGrant = scheduler.platformReport().threads().get(CriticalityDeadlinePlacement.HIGH_DISPATCHER);
        if (highGrant.granted().isRealtime()) {
            assertEquals(highGrant.granted(), lowDispatcherWhileHighWaits,
                    "the LOW dispatcher inherits the waiting HIGH job's priority, read back from the OS");
            assertEquals(1, scheduler.stats().dispatcher(CriticalityDeadlinePlacement.LOW_DISPATCHER)
                    .priorityBoosts());
            awaitOsPolicy(CriticalityDeadlinePlacement.LOW_DISPATCHER, lowGrant.granted());
        } else {
            assertEquals(lowGrant.granted(), lowDispatcherWhileHighWaits, "nothing to inherit without SCHED_FIFO");
            assertEquals(0, scheduler.stats().dispatcher(CriticalityDeadlinePlacement.LOW_DISPATCHER)
                    .priorityBoosts());
        }
    }

    @Test
    void shouldNotRaiseTheHolderWhenPriorityInheritanceIsOff() throws Exception {
        var lowRunning = new CountDownLatch(1);
        var releaseLow = new CountDownLatch(1);
        var done = new CountDownLatch(2);
        var kernel = new FakeKernel().on("C", (job, startNs) -> {
            if (job.message().qos().criticality() == Criticality.LOW) {
                lowRunning.countDown();
                releaseLow.await(LOW_WCET_MS, TimeUnit.MILLISECONDS);
            }
            done.countDown();
        });
        scheduler = new RealtimeScheduler(RealtimeSchedulerConfig.builder().priorityInheritance(false).build());
        kernel.bind(scheduler);
        scheduler.start(kernel, NodeClock.system());
        scheduler.submit(job("C", QoS.periodic(Criticality.LOW, PERIOD_NS), System.nanoTime()));
        assertTrue(lowRunning.await(5, TimeUnit.SECONDS));
        scheduler.submit(job("C", QoS.periodic(Criticality.HIGH, PERIOD_NS), System.nanoTime()));
        awaitParked(CriticalityDeadlinePlacement.HIGH_DISPATCHER, 1);

        ThreadPolicy whileWaiting = osPolicyOf(CriticalityDeadlinePlacement.LOW_DISPATCHER);
        releaseLow.countDown();
        assertTrue(done.await(5, TimeUnit.SECONDS));

        assertEquals(scheduler.platformReport().threads().get(CriticalityDeadlinePlacement.LOW_DISPATCHER).granted(),
                whileWaiting);
        assertEquals(0, scheduler.stats().dispatcher(CriticalityDeadlinePlacement.LOW_DISPATCHER).priorityBoosts());
    }

    private ThreadPolicy osPolicyOf(int dispatcherId) {
        int tid = scheduler.platformReport().threads().get(dispatcherId).osThreadId();
        return Platform.current().threadPolicy(tid).orElse(ThreadPolicy.NON_REALTIME);
    }

    private void awaitOsPolicy(int dispatcherId, ThreadPolicy expected) throws InterruptedException {
        long deadlineNs = System.nanoTime() + TimeUnit.SECONDS.toNanos(5);
        while (!osPolicyOf(dispatcherId).equals(expected) && System.nanoTime() < deadlineNs) {
            Thread.sleep(1);
        }
        assertEquals(expected, osPolicyOf(dispatcherId), "back to its own priority after the job");
    }

    private void awaitParked(int dispatcherId, long count) throws InterruptedException {
        long deadlineNs = System.nanoTime() + TimeUnit.SECONDS.toNanos(5);
        while (scheduler.stats().dispatcher(dispatcherId).jobsParked() < count && System.nanoTime() < deadlineNs) {
            Thread.sleep(1);
        }
        assertEquals(count, scheduler.stats().dispatcher(dispatcherId).jobsParked());
    }

}
