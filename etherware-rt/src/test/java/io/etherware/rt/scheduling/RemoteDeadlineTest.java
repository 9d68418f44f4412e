package io.etherware.rt.scheduling;

import static org.junit.jupiter.api.Assertions.assertEquals;
import static org.junit.jupiter.api.Assertions.assertTrue;

import io.etherware.core.kernel.EtherwareNode;
import io.etherware.core.message.Criticality;
import io.etherware.core.message.Message;
import io.etherware.core.message.MessageId;
import io.etherware.core.message.Origin;
import io.etherware.core.message.Profile;
import io.etherware.core.message.QoS;
import io.etherware.core.message.Text;
import java.util.concurrent.CopyOnWriteArrayList;
import java.util.concurrent.TimeUnit;
import java.util.concurrent.atomic.AtomicInteger;
import org.junit.jupiter.api.Test;

/**
 * Deadlines are absolute across nodes: a message from another node is released when it was made
 * there (its translated time stamp), so one that arrives past its deadline is a miss.
 */
class RemoteDeadlineTest {

    private static final Profile SENSOR = Profile.of("sensor");
    private static final long DEADLINE_NS = TimeUnit.MILLISECONDS.toNanos(10);

    @Test
    void shouldCountAMessageFromAnotherNodeThatArrivesPastItsDeadlineAsAMiss() throws Exception {
        var misses = new CopyOnWriteArrayList<DeadlineMiss>();
        var handled = new AtomicInteger();
        var scheduler = RealtimeSchedulerConfig.builder().threadSchedulingRule(ThreadSchedulingRule.nonRealtime(4))
                .deadlineMissHandler(misses::add).build();
        try (var node = EtherwareNode.builder().nodeId("receiver")
                .scheduler(() -> new RealtimeScheduler(scheduler)).build()) {
            node.add(SENSOR, () -> (message, context) -> handled.incrementAndGet());
            node.start();
            QoS qos = QoS.of(Criticality.HIGH).withDeadlineNs(DEADLINE_NS);
            long nowEpochNs = node.clock().epochNanos();
            // Made 50 ms ago on node 'far' (five deadlines): late on arrival.
            node.send(remote(nowEpochNs - TimeUnit.MILLISECONDS.toNanos(50), qos, 1));
            // Made just now: in time.
            node.send(remote(node.clock().epochNanos(), qos, 2));
            // Made here 50 ms "ago" by the same stamp: a local message's deadline counts from its
            // arrival, as before (its time stamp is this node's, not a transit).
            node.send(new Message(SENSOR, null, nowEpochNs - TimeUnit.MILLISECONDS.toNanos(50), qos,
                    new Text("local"), node.newMessageId(), null));

            long deadlineNs = System.nanoTime() + TimeUnit.SECONDS.toNanos(30);
            while (handled.get() < 3 && System.nanoTime() < deadlineNs) {
                Thread.sleep(1);
            }
            assertEquals(3, handled.get());
            Thread.sleep(50); // the miss handler runs after the handling
            assertEquals(1, misses.size(), "only the late remote message missed: " + misses);
            DeadlineMiss miss = misses.getFirst();
            assertEquals(new MessageId("far", 1), miss.messageId());
            assertTrue(miss.latenessNs() >= TimeUnit.MILLISECONDS.toNanos(35),
                    "late by about 40 ms on arrival: " + miss.latenessNs() + " ns");
        }
    }

    private static Message remote(long timeStampEpochNs, QoS qos, long sequence) {
        return new Message(SENSOR, null, timeStampEpochNs, qos, new Text("reading"), new MessageId("far", sequence),
                null, Origin.direct("far", true));
    }
}
