package io.etherware.services.network.internal;

import static org.junit.jupiter.api.Assertions.assertEquals;
import static org.junit.jupiter.api.Assertions.assertInstanceOf;
import static org.junit.jupiter.api.Assertions.assertNull;
import static org.junit.jupiter.api.Assertions.assertSame;

import io.etherware.core.message.Criticality;
import io.etherware.core.message.Message;
import io.etherware.core.message.MessageId;
import io.etherware.core.message.Profile;
import io.etherware.core.message.QoS;
import io.etherware.core.message.Text;
import java.util.ArrayList;
import java.util.List;
import org.junit.jupiter.api.Test;

class OutboundQueueTest {

    private static long sequence;

    private static Outgoing message(Criticality criticality) {
        return new Outgoing(new Message(Profile.of("x"), null, 0, QoS.of(criticality), new Text(criticality.name()),
                new MessageId("a", sequence++), null), 0, null);
    }

    private static List<Outgoing> drain(OutboundQueue queue) {
        var all = new ArrayList<Outgoing>();
        Outgoing next;
        while ((next = queue.poll()) != null) {
            all.add(next);
        }
        return all;
    }

    @Test
    void shouldTakeTheMostCriticalFirstAndFifoWithinALevel() {
        var queue = new OutboundQueue(10);
        Outgoing low1 = message(Criticality.LOW);
        Outgoing high1 = message(Criticality.HIGH);
        Outgoing none = message(Criticality.NONE);
        Outgoing middle = message(Criticality.MIDDLE);
        Outgoing high2 = message(Criticality.HIGH);
        Outgoing low2 = message(Criticality.LOW);
        for (Outgoing each : List.of(low1, high1, none, middle, high2, low2)) {
            assertSame(OutboundQueue.Outcome.QUEUED, queue.offer(each));
        }
        assertEquals(List.of(high1, high2, middle, low1, low2, none), drain(queue));
        assertNull(queue.poll());
    }

    @Test
    void shouldEvictTheOldestLeastCriticalToMakeRoomForAMoreCriticalMessage() {
        var queue = new OutboundQueue(3);
        Outgoing low = message(Criticality.LOW);
        Outgoing none1 = message(Criticality.NONE);
        Outgoing none2 = message(Criticality.NONE);
        queue.offer(low);
        queue.offer(none1);
        queue.offer(none2);
        Outgoing high = message(Criticality.HIGH);
        assertEquals(new OutboundQueue.Outcome.Evicted(none1), queue.offer(high), "NONE goes first, oldest first");
        Outgoing middle = message(Criticality.MIDDLE);
        assertEquals(new OutboundQueue.Outcome.Evicted(none2), queue.offer(middle));
        assertEquals(new OutboundQueue.Outcome.Evicted(low), queue.offer(message(Criticality.HIGH)));
        assertEquals(3, queue.size());
    }

    @Test
    void shouldRefuseAMessageWhenEverythingQueuedIsAtLeastAsCritical() {
        var queue = new OutboundQueue(2);
        queue.offer(message(Criticality.HIGH));
        queue.offer(message(Criticality.MIDDLE));
        assertInstanceOf(OutboundQueue.Outcome.Full.class, queue.offer(message(Criticality.MIDDLE)));
        assertInstanceOf(OutboundQueue.Outcome.Full.class, queue.offer(message(Criticality.LOW)));
        assertInstanceOf(OutboundQueue.Outcome.Evicted.class, queue.offer(message(Criticality.HIGH)));
        assertInstanceOf(OutboundQueue.Outcome.Full.class, queue.offer(message(Criticality.HIGH)));
    }

    @Test
    void shouldPutBackTakenMessagesAheadOfTheRestInTheirOrder() {
        var queue = new OutboundQueue(10);
        Outgoing first = message(Criticality.HIGH);
        Outgoing second = message(Criticality.HIGH);
        Outgoing third = message(Criticality.HIGH);
        queue.offer(first);
        queue.offer(second);
        queue.offer(third);
        List<Outgoing> taken = List.of(queue.poll(), queue.poll());
        queue.pushBack(taken);
        assertEquals(List.of(first, second, third), drain(queue));
    }
}
