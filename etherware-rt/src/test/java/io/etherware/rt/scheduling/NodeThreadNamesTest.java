package io.etherware.rt.scheduling;

import static org.junit.jupiter.api.Assertions.assertEquals;

import io.etherware.core.kernel.EtherwareNode;
import io.etherware.core.message.Criticality;
import io.etherware.core.message.Profile;
import io.etherware.core.message.QoS;
import io.etherware.core.message.Text;
import io.etherware.core.scheduler.FifoScheduler;
import io.etherware.core.scheduler.Scheduler;
import java.util.concurrent.CompletableFuture;
import java.util.concurrent.TimeUnit;
import java.util.function.Supplier;
import org.junit.jupiter.api.Test;

/** Two nodes in one JVM can be told apart in a thread dump: each dispatcher's name ends with its node's id. */
class NodeThreadNamesTest {

    private static final Profile ECHO = Profile.of("echo");

    @Test
    void shouldNameEachRealtimeDispatcherAfterItsNodeWhenTwoNodesShareAJvm() throws Exception {
        assertEquals("rt-dispatcher-1@plant", threadThatRan("plant", RealtimeScheduler::withDefaults, Criticality.HIGH));
        assertEquals("rt-dispatcher-3@control", threadThatRan("control", RealtimeScheduler::withDefaults, Criticality.LOW));
    }

    @Test
    void shouldNameTheFifoDispatcherAfterItsNode() throws Exception {
        assertEquals("etherware-fifo@plant", threadThatRan("plant", FifoScheduler::new, Criticality.HIGH));
    }

    private static String threadThatRan(String nodeId, Supplier<? extends Scheduler> scheduler, Criticality criticality)
            throws Exception {
        var ran = new CompletableFuture<String>();
        try (var node = EtherwareNode.builder().nodeId(nodeId).scheduler(scheduler).build()) {
            node.add(ECHO, () -> (message, context) -> ran.complete(Thread.currentThread().getName()));
            node.start();
            node.send(ECHO, new Text("who runs me"), QoS.periodic(criticality, TimeUnit.MILLISECONDS.toNanos(15)));
            return ran.get(10, TimeUnit.SECONDS);
        }
    }
}
