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
                new MessageId("a", sequence++), null), 0, new byte[100], -1, 0);
    }

    private static Outgoing sized(Criticality criticality, int bytes) {
        return new Outgoing(message(criticality).message(), 0, new byte[bytes], -1, 0);
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
            assertSame(OutboundQueue.Outcome.QUEUED, queue.offer(each, Long.MAX_VALUE));
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
        queue.offer(low, Long.MAX_VALUE);
        queue.offer(none1, Long.MAX_VALUE);
        queue.offer(none2, Long.MAX_VALUE);
        Outgoing high = message(Criticality.HIGH);
        assertEquals(new OutboundQueue.Outcome.Evicted(List.of(none1)), queue.offer(high, Long.MAX_VALUE), "NONE goes first, oldest first");
        Outgoing middle = message(Criticality.MIDDLE);
        assertEquals(new OutboundQueue.Outcome.Evicted(List.of(none2)), queue.offer(middle, Long.MAX_VALUE));
        assertEquals(new OutboundQueue.Outcome.Evicted(List.of(low)), queue.offer(message(Criticality.HIGH), Long.MAX_VALUE));
        assertEquals(3, queue.size());
    }

    @Test
    void shouldRefuseAMessageWhenEverythingQueuedIsAtLeastAsCritical() {
        var queue = new OutboundQueue(2);
        queue.offer(message(Criticality.HIGH), Long.MAX_VALUE);
        queue.offer(message(Criticality.MIDDLE), Long.MAX_VALUE);
        assertInstanceOf(OutboundQueue.Outcome.Full.class, queue.offer(message(Criticality.MIDDLE), Long.MAX_VALUE));
        assertInstanceOf(OutboundQueue.Outcome.Full.class, queue.offer(message(Criticality.LOW), Long.MAX_VALUE));
        assertInstanceOf(OutboundQueue.Outcome.Evicted.class, queue.offer(message(Criticality.HIGH), Long.MAX_VALUE));
        assertInstanceOf(OutboundQueue.Outcome.Full.class, queue.offer(message(Criticality.HIGH), Long.MAX_VALUE));
    }

    @Test
    void shouldPutBackTakenMessagesAheadOfTheRestInTheirOrder() {
        var queue = new OutboundQueue(10);
        Outgoing first = message(Criticality.HIGH);
        Outgoing second = message(Criticality.HIGH);
        Outgoing third = message(Criticality.HIGH);
        queue.offer(first, Long.MAX_VALUE);
        queue.offer(second, Long.MAX_VALUE);
        queue.offer(third, Long.MAX_VALUE);
        List<Outgoing> taken = List.of(queue.poll(), queue.poll());
        queue.pushBack(taken);
        assertEquals(List.of(first, second, third), drain(queue));
    }

    @Test
    void shouldEvictLessCriticalMessagesUntilTheBytesFitAndRefuseWhenTheyCannot() {
        var queue = new OutboundQueue(100);
        Outgoing low1 = sized(Criticality.LOW, 400);
        Outgoing low2 = sized(Criticality.LOW, 400);
        Outgoing middle = sized(Criticality.MIDDLE, 100);
        assertSame(OutboundQueue.Outcome.QUEUED, queue.offer(low1, 1000));
        assertSame(OutboundQueue.Outcome.QUEUED, queue.offer(low2, 1000));
        assertSame(OutboundQueue.Outcome.QUEUED, queue.offer(middle, 1000));
        assertEquals(900, queue.bytes());

        Outgoing high = sized(Criticality.HIGH, 700);
        assertEquals(new OutboundQueue.Outcome.Evicted(List.of(low1, low2)), queue.offer(high, 1000),
                "both LOW messages go to make 700 bytes of room, the MIDDLE one stays");
        assertEquals(800, queue.bytes());
        assertInstanceOf(OutboundQueue.Outcome.Full.class, queue.offer(sized(Criticality.HIGH, 400), 1000),
                "only the MIDDLE message of 100 bytes is evictable: not enough for 200");
        assertInstanceOf(OutboundQueue.Outcome.Full.class, queue.offer(sized(Criticality.LOW, 300), 1000));
        assertEquals(List.of(high, middle), drain(queue));
        assertEquals(0, queue.bytes());
    }
}
