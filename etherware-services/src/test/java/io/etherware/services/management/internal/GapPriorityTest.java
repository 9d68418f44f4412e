package io.etherware.services.management.internal;

import static org.junit.jupiter.api.Assertions.assertEquals;
import static org.junit.jupiter.api.Assumptions.assumeTrue;

import io.etherware.core.kernel.EtherwareNode;
import io.etherware.core.message.Criticality;
import io.etherware.core.message.Profile;
import io.etherware.core.message.QoS;
import io.etherware.core.scheduler.FifoScheduler;
import io.etherware.rt.platform.Platform;
import io.etherware.rt.platform.SchedulingPolicy;
import io.etherware.rt.platform.ThreadPolicy;
import io.etherware.rt.scheduling.RealtimeScheduler;
import io.etherware.rt.scheduling.RealtimeSchedulerConfig;
import io.etherware.rt.scheduling.ThreadSchedulingRule;
import java.util.concurrent.Callable;
import java.util.concurrent.CompletableFuture;
import java.util.concurrent.TimeUnit;
import org.junit.jupiter.api.Test;

/**
 * The migration gap's thread policy: taken from the node's real-time scheduler, given to the
 * calling thread for the gap and taken back afterwards, also when the gap ends with an error.
 * Each case runs on a thread of its own, so the test runner's threads never change policy.
 */
class GapPriorityTest {

    /** Low enough not to matter on a shared machine; the thread only reads its own policy. */
    private static final ThreadPolicy LOW_FIFO = new ThreadPolicy(SchedulingPolicy.FIFO, 5);

    private static <T> T onOwnThread(Callable<T> body) throws Exception {
        var result = new CompletableFuture<T>();
        Thread.ofPlatform().name("gap-priority-test").start(() -> {
            try {
                result.complete(body.call());
            } catch (Throwable e) {
                result.completeExceptionally(e);
            }
        });
        return result.get(30, TimeUnit.SECONDS);
    }

    @Test
    void shouldRunTheGapAtTheRealtimePolicyAndGiveTheThreadItsOwnBackAfterwards() throws Exception {
        var policies = onOwnThread(() -> {
            Platform platform = Platform.current();
            ThreadPolicy before = platform.currentThreadPolicy();
            ThreadPolicy during;
            try (var raised = new GapPriority(LOW_FIFO).raise()) {
                during = platform.currentThreadPolicy();
            }
            return new ThreadPolicy[] {before, during, platform.currentThreadPolicy()};
        });
        assumeTrue(policies[1].isRealtime(), "SCHED_FIFO is not granted here, so there is nothing to take back");
        assertEquals(ThreadPolicy.NON_REALTIME, policies[0], "an ordinary thread to begin with");
        assertEquals(LOW_FIFO, policies[1], "the gap's policy during the gap");
        assertEquals(policies[0], policies[2], "its own policy again after the gap");
    }

    @Test
    void shouldGiveThePolicyBackWhenTheGapEndsWithAnError() throws Exception {
        var policies = onOwnThread(() -> {
            Platform platform = Platform.current();
            ThreadPolicy during = null;
            try (var raised = new GapPriority(LOW_FIFO).raise()) {
                during = platform.currentThreadPolicy();
                throw new IllegalStateException("the step failed");
            } catch (IllegalStateException expected) {
                return new ThreadPolicy[] {during, platform.currentThreadPolicy()};
            }
        });
        assumeTrue(policies[0].isRealtime(), "SCHED_FIFO is not granted here");
        assertEquals(ThreadPolicy.NON_REALTIME, policies[1]);
    }

    @Test
    void shouldLeaveTheThreadAsItIsWithoutARealtimePolicy() throws Exception {
        var policy = onOwnThread(() -> {
            try (var raised = new GapPriority(ThreadPolicy.NON_REALTIME).raise()) {
                return Platform.current().currentThreadPolicy();
            }
        });
        assertEquals(ThreadPolicy.NON_REALTIME, policy);
    }

    @Test
    void shouldTakeThePolicyOfTheRequestsDispatcherFromARealtimeSchedulerAndNoneFromAnother() {
        Profile service = Profile.of("etherware.management", "node", "gap-rt");
        try (var realtime = EtherwareNode.builder().nodeId("gap-rt").scheduler(() -> new RealtimeScheduler(
                RealtimeSchedulerConfig.builder().threadSchedulingRule(ThreadSchedulingRule.tableII()).build())).build();
                var fifo = EtherwareNode.builder().nodeId("gap-fifo").scheduler(FifoScheduler::new).build()) {
            assertEquals(new ThreadPolicy(SchedulingPolicy.FIFO, 80),
                    GapPriority.of(realtime, service, QoS.of(Criticality.HIGH)).policy(), "Table II's dispatcher 1");
            assertEquals(new ThreadPolicy(SchedulingPolicy.FIFO, 60),
                    GapPriority.of(realtime, service, QoS.of(Criticality.LOW)).policy(), "Table II's dispatcher 3");
            assertEquals(ThreadPolicy.NON_REALTIME, GapPriority.of(realtime, service, QoS.NONE).policy(),
                    "a request without QoS: dispatcher 0, ordinary");
            assertEquals(ThreadPolicy.NON_REALTIME, GapPriority.of(fifo, service, QoS.of(Criticality.HIGH)).policy());
        }
    }
}
