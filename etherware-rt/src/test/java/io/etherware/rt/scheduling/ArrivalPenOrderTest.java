package io.etherware.rt.scheduling;

import static org.junit.jupiter.api.Assertions.assertEquals;

import io.etherware.core.kernel.EtherwareNode;
import io.etherware.core.message.Contents;
import io.etherware.core.message.Criticality;
import io.etherware.core.message.Profile;
import io.etherware.core.message.QoS;
import io.etherware.testkit.Await;
import java.util.List;
import java.util.concurrent.CopyOnWriteArrayList;
import org.junit.jupiter.api.Test;

/**
 * The arrival pen of a migration (the management package's ordering argument) under the
 * real-time scheduler: a message sent directly to an arriving component must be handled after
 * the ones forwarded by the source, which were sent before it. This scheduler orders by a key
 * taken at the submission (for an aperiodic message the submission time) before the sequence, so
 * an offset on the sequence alone would let the direct message, submitted first, run first
 * (handled [9, 0, 1]); the kernel therefore defers its submission until the admission. The
 * core's test of the same order runs under the default scheduler, whose urgency is the sequence.
 */
class ArrivalPenOrderTest {

    record Num(long value) implements Contents {
    }

    @Test
    void shouldHandleForwardedMessagesBeforeThoseSentDirectlyUnderTheRealtimeScheduler() throws Exception {
        Profile target = Profile.of("counter", "test", "pen");
        Profile arrival = Profile.of("etherware.arrival", "id", "pen-1");
        var handled = new CopyOnWriteArrayList<Long>();
        QoS middle = QoS.of(Criticality.MIDDLE);
        try (var node = EtherwareNode.builder().nodeId("pen").scheduler(() -> new RealtimeScheduler(
                RealtimeSchedulerConfig.builder().threadSchedulingRule(ThreadSchedulingRule.tableII().withoutRealtime())
                        .build())).build().start()) {
            node.addHeld(target, arrival, () -> (message, context) -> handled.add(((Num) message.contents()).value()),
                    ns -> { });
            node.send(target, new Num(9), middle); // sent here directly: penned behind the forwarded ones
            Thread.sleep(2);
            node.send(arrival, new Num(0), middle); // forwarded by the source, though it comes later
            node.send(arrival, new Num(1), middle);
            node.admit(arrival, 2);
            Await.until("three handled", () -> handled.size() == 3);
            node.send(target, new Num(10), middle); // after the admission: in the order sent
            Await.until("four handled", () -> handled.size() == 4);
            assertEquals(List.of(0L, 1L, 9L, 10L), handled, "forwarded first, then penned, then later ones");
        }
    }
}
