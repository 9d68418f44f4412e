package io.etherware.core.kernel;

import static org.junit.jupiter.api.Assertions.assertEquals;
import static org.junit.jupiter.api.Assertions.assertTrue;

import io.etherware.core.message.Message;
import io.etherware.core.message.MessageId;
import io.etherware.core.message.Origin;
import io.etherware.core.message.Profile;
import io.etherware.core.message.QoS;
import io.etherware.core.message.Text;
import java.util.concurrent.CountDownLatch;
import java.util.concurrent.TimeUnit;
import java.util.concurrent.atomic.AtomicInteger;
import org.junit.jupiter.api.Test;

/** The bytes a peer makes a node hold: counted while its messages wait, released when handled. */
class InboundAccountingTest {

    private static final Profile SLOW = Profile.of("slow");

    private static Message fromNetwork(String via, long sequence, int wireBytes) {
        return new Message(SLOW, null, 0, QoS.NONE, new Text("x"), new MessageId(via, sequence), null,
                new Origin(via, via, 0, true, wireBytes));
    }

    @Test
    void shouldCountQueuedBytesByTheNodeTheyCameThroughUntilHandled() throws Exception {
        var entered = new CountDownLatch(1);
        var finish = new CountDownLatch(1);
        var handled = new AtomicInteger();
        try (var node = EtherwareNode.builder().nodeId("receiver").build()) {
            node.add(SLOW, () -> (message, context) -> {
                if (handled.getAndIncrement() == 0) {
                    entered.countDown();
                    assertTrue(finish.await(30, TimeUnit.SECONDS));
                }
            });
            node.start();
            node.send(fromNetwork("peer-a", 0, 1000));
            assertTrue(entered.await(30, TimeUnit.SECONDS));
            node.send(fromNetwork("peer-a", 1, 300));
            node.send(fromNetwork("peer-b", 0, 50));
            node.send(new Message(SLOW, null, 0, QoS.NONE, new Text("local"), node.newMessageId(), null));

            assertEquals(1300, node.queuedBytesFrom("peer-a"), "the one in its handler and the one waiting");
            assertEquals(50, node.queuedBytesFrom("peer-b"));
            assertEquals(0, node.queuedBytesFrom("receiver"), "local messages are not counted");

            finish.countDown();
            long deadlineNs = System.nanoTime() + TimeUnit.SECONDS.toNanos(30);
            while (handled.get() < 4 && System.nanoTime() < deadlineNs) {
                Thread.sleep(1);
            }
            assertEquals(4, handled.get());
            // Counted down after the handler returns, before the next job: poll briefly for the last.
            while ((node.queuedBytesFrom("peer-a") != 0 || node.queuedBytesFrom("peer-b") != 0)
                    && System.nanoTime() < deadlineNs) {
                Thread.sleep(1);
            }
            assertEquals(0, node.queuedBytesFrom("peer-a"));
            assertEquals(0, node.queuedBytesFrom("peer-b"));
        }
    }

    @Test
    void shouldReleaseTheBytesOfMessagesKeptAtAHoldWhenARelocationForwardsThem() throws Exception {
        var forwarded = new java.util.concurrent.CopyOnWriteArrayList<Message>();
        try (var node = EtherwareNode.builder().nodeId("receiver").build()) {
            node.add(SLOW, () -> (message, context) -> { });
            node.start();
            node.holdAsync(SLOW).get(30, TimeUnit.SECONDS);
            node.send(fromNetwork("peer-a", 0, 1000));
            node.send(fromNetwork("peer-a", 1, 300));
            assertEquals(1300, node.queuedBytesFrom("peer-a"));
            Thread.sleep(100); // both reach the gate and are kept there
            node.relocateAsync(SLOW, forwarded::add).get(30, TimeUnit.SECONDS);
            assertEquals(2, forwarded.size(), "both kept messages went to the route");
            assertEquals(0, node.queuedBytesFrom("peer-a"), "what was forwarded no longer holds the peer's budget");
        }
    }
}
