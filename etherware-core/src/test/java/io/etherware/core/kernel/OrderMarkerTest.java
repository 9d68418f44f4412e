package io.etherware.core.kernel;

import static org.junit.jupiter.api.Assertions.assertEquals;
import static org.junit.jupiter.api.Assertions.assertFalse;
import static org.junit.jupiter.api.Assertions.assertInstanceOf;
import static org.junit.jupiter.api.Assertions.assertNull;
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
import java.util.concurrent.CompletableFuture;
import java.util.concurrent.CopyOnWriteArrayList;
import java.util.concurrent.CountDownLatch;
import java.util.concurrent.TimeUnit;
import org.junit.jupiter.api.Test;

/**
 * An {@link OrderMarker} that reaches the node hosting its component is answered to the node the
 * connection vouches for, as a message of its own; the component never sees it. The answers are
 * seen by a tap on what the node sends (on a real node the network takes them).
 */
class OrderMarkerTest {

    private static final Profile SLOW = Profile.of("slow");
    private static final Profile PEER_NODE = Profile.of("etherware.node", "id", "peer");
    private static final Profile NAMED_SENDER = Profile.of("somewhere-else");

    private static Message fromPeer(Profile to, long sequence, Contents contents) {
        return new Message(to, NAMED_SENDER, 0, QoS.of(Criticality.MIDDLE), contents, new MessageId("peer", sequence),
                null, new Origin("peer", "peer", 0, true, 100));
    }

    private static List<Message> answersOf(EtherwareNode node, List<Message> into) {
        node.tap(message -> {
            if (message.contents() instanceof OrderMarker) {
                into.add(message);
            }
        });
        return into;
    }

    private static void awaitTrue(java.util.function.BooleanSupplier condition) throws InterruptedException {
        long deadlineNs = System.nanoTime() + TimeUnit.SECONDS.toNanos(30);
        while (!condition.getAsBoolean() && System.nanoTime() < deadlineNs) {
            Thread.sleep(1);
        }
    }

    @Test
    void shouldAnswerAMarkerToItsOriginNodeOnceQueuedAndNeverHandItToTheComponent() throws Exception {
        var entered = new CountDownLatch(1);
        var finish = new CountDownLatch(1);
        var handled = new CopyOnWriteArrayList<String>();
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
            node.start();
            var seen = answersOf(node, new CopyOnWriteArrayList<>());

            node.send(fromPeer(SLOW, 0, new Text("first")));
            assertTrue(entered.await(30, TimeUnit.SECONDS));
            node.send(fromPeer(SLOW, 1, new Text("second")));
            node.send(fromPeer(SLOW, 2, new OrderMarker(42)));
            node.send(fromPeer(SLOW, 3, new Text("third")));
            awaitTrue(() -> seen.size() >= 2);

            // The marker as it came in, then the answer: while "second" still waits its turn.
            assertEquals(2, seen.size(), "the marker and one answer: " + seen);
            Message answer = seen.get(1);
            assertEquals(PEER_NODE, answer.profile(), "to the node the connection vouches for");
            assertEquals(42, assertInstanceOf(OrderMarker.class, answer.contents()).token());
            assertNull(answer.correlationId(), "a message of its own, not a reply: it completes no request");
            assertEquals(List.of("first"), handled, "answered once queued, before the earlier ones ran");

            finish.countDown();
            awaitTrue(() -> handled.size() >= 3);
            Thread.sleep(20);
            assertEquals(List.of("first", "second", "third"), handled, "the component never saw the marker");
            assertTrue(toNamedSender.isEmpty(), "never to the profile the marker names as its sender");
            assertEquals(0, node.stats().undeliverable());
        }
    }

    @Test
    void shouldAnswerAMarkerForAProfileNothingHostsInsteadOfReportingItUndeliverable() throws Exception {
        try (var node = EtherwareNode.builder().nodeId("host").build()) {
            node.start();
            var seen = answersOf(node, new CopyOnWriteArrayList<>());
            node.send(fromPeer(Profile.of("gone"), 5, new OrderMarker(9)));
            awaitTrue(() -> seen.size() >= 2);
            assertEquals(PEER_NODE, seen.get(1).profile());
            assertEquals(0, node.stats().undeliverable(), "nothing the sender must hear about");
        }
    }

    @Test
    void shouldNotAnswerAMarkerThatClaimsToComeFromThisNodeSoNoPendingRequestCanBeForged() throws Exception {
        try (var node = EtherwareNode.builder().nodeId("host").build()) {
            node.add(SLOW, () -> (message, context) -> { });
            node.start();
            var seen = answersOf(node, new CopyOnWriteArrayList<>());
            // A request of this node's own, pending (the component never answers), and a marker a
            // peer relays under this node's id and that request's id: an answer made here would go
            // to this node, about that id.
            MessageId requestId = node.newMessageId();
            CompletableFuture<Message> pending = node.request(new Message(SLOW, node.profile(), 0, QoS.NONE,
                    new Text("?"), requestId, null), TimeUnit.SECONDS.toNanos(30));
            node.send(new Message(SLOW, node.profile(), 0, QoS.NONE, new OrderMarker(1), requestId, null,
                    new Origin("host", "peer", 1, true, 100)));
            node.send(SLOW, new OrderMarker(7), QoS.of(Criticality.MIDDLE)); // made here
            Thread.sleep(100);
            assertEquals(2, seen.size(), "the two markers, no answer: " + seen);
            assertFalse(pending.isDone(), "the pending request is still pending");
        }
    }
}
