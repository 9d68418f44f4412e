package io.etherware.core.kernel;

import static org.junit.jupiter.api.Assertions.assertEquals;
import static org.junit.jupiter.api.Assertions.assertInstanceOf;
import static org.junit.jupiter.api.Assertions.assertTrue;

import io.etherware.core.message.Contents;
import io.etherware.core.message.Criticality;
import io.etherware.core.message.Message;
import io.etherware.core.message.MessageId;
import io.etherware.core.message.Origin;
import io.etherware.core.message.Profile;
import io.etherware.core.message.QoS;
import io.etherware.core.message.Text;
import java.util.List;
import java.util.concurrent.CopyOnWriteArrayList;
import java.util.concurrent.CountDownLatch;
import java.util.concurrent.TimeUnit;
import org.junit.jupiter.api.Test;

/**
 * An {@link OrderMarker} is answered when its turn comes at the component, behind its sender's
 * earlier messages, to the node the connection vouches for; the component never sees it. The
 * answers are seen by a tap on what the node sends (on a real node the network takes them).
 */
class OrderMarkerTest {

    private static final Profile SLOW = Profile.of("slow");
    private static final Profile PEER_NODE = Profile.of("etherware.node", "id", "peer");
    private static final Profile NAMED_SENDER = Profile.of("somewhere-else");

    private static Message fromPeer(long sequence, Contents contents) {
        return new Message(SLOW, NAMED_SENDER, 0, QoS.of(Criticality.MIDDLE), contents,
                new MessageId("peer", sequence), null, new Origin("peer", "peer", 0, true, 100));
    }

    @Test
    void shouldAnswerAMarkerToItsOriginNodeAfterTheEarlierMessagesAndNeverHandItToTheComponent() throws Exception {
        var entered = new CountDownLatch(1);
        var finish = new CountDownLatch(1);
        var handled = new CopyOnWriteArrayList<String>();
        var answers = new CopyOnWriteArrayList<Message>();
        var toNamedSender = new CopyOnWriteArrayList<Message>();
        try (var node = EtherwareNode.builder().nodeId("host").build()) {
            node.add(SLOW, () -> (message, context) -> {
                handled.add(((Text) message.contents()).text());
                if (handled.size() == 1) {
                    entered.countDown();
                    assertTrue(finish.await(30, TimeUnit.SECONDS));
                }
            });
            node.add(NAMED_SENDER, () -> (message, context) -> toNamedSender.add(message));
            node.tap(message -> {
                if (message.profile().equals(PEER_NODE)) {
                    answers.add(message);
                }
            });
            node.start();

            node.send(fromPeer(0, new Text("first")));
            assertTrue(entered.await(30, TimeUnit.SECONDS));
            node.send(fromPeer(1, new Text("second")));
            node.send(fromPeer(2, new OrderMarker(42)));
            node.send(fromPeer(3, new Text("third")));
            Thread.sleep(50);
            assertTrue(answers.isEmpty(), "not answered while an earlier message waits: " + answers);

            finish.countDown();
            long deadlineNs = System.nanoTime() + TimeUnit.SECONDS.toNanos(30);
            while ((answers.isEmpty() || handled.size() < 3) && System.nanoTime() < deadlineNs) {
                Thread.sleep(1);
            }
            assertEquals(List.of("first", "second", "third"), handled, "the component never saw the marker");
            assertEquals(1, answers.size());
            Message answer = answers.getFirst();
            assertEquals(42, assertInstanceOf(OrderMarker.class, answer.contents()).token());
            assertEquals(new MessageId("peer", 2), answer.correlationId(), "a reply to the marker");
            assertTrue(toNamedSender.isEmpty(), "never to the profile the marker names as its sender");
        }
    }

    @Test
    void shouldNotAnswerAMarkerMadeOnThisNode() throws Exception {
        var handled = new CopyOnWriteArrayList<Message>();
        var answers = new CopyOnWriteArrayList<Message>();
        try (var node = EtherwareNode.builder().nodeId("host").build()) {
            node.add(SLOW, () -> (message, context) -> handled.add(message));
            node.tap(message -> {
                if (message.contents() instanceof OrderMarker && message.isReply()) {
                    answers.add(message);
                }
            });
            node.start();
            node.send(SLOW, new OrderMarker(7), QoS.of(Criticality.MIDDLE));
            node.send(SLOW, new Text("after"), QoS.of(Criticality.MIDDLE));
            long deadlineNs = System.nanoTime() + TimeUnit.SECONDS.toNanos(30);
            while (handled.isEmpty() && System.nanoTime() < deadlineNs) {
                Thread.sleep(1);
            }
            assertEquals(1, handled.size(), "only the text: " + handled);
            assertInstanceOf(Text.class, handled.getFirst().contents());
            assertTrue(answers.isEmpty());
        }
    }
}
