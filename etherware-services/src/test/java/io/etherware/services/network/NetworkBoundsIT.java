package io.etherware.services.network;

import static org.junit.jupiter.api.Assertions.assertEquals;
import static org.junit.jupiter.api.Assertions.assertThrows;
import static org.junit.jupiter.api.Assertions.assertTrue;

import io.etherware.core.codec.MessageCodec;
import io.etherware.core.message.ContentsTypes;
import io.etherware.core.message.Criticality;
import io.etherware.core.message.Message;
import io.etherware.core.message.MessageId;
import io.etherware.core.message.Profile;
import io.etherware.core.message.QoS;
import io.etherware.core.message.Text;
import io.etherware.core.time.NodeClock;
import io.etherware.testkit.Await;
import java.net.InetSocketAddress;
import java.time.Duration;
import java.util.List;
import java.util.concurrent.CopyOnWriteArrayList;
import java.util.concurrent.CountDownLatch;
import java.util.concurrent.TimeUnit;
import org.junit.jupiter.api.Test;

/** What a peer can make a node hold is bounded in bytes, both ways, and nothing honest is lost. */
class NetworkBoundsIT {

    private static final Profile SLOW = Profile.of("slow");
    private static final int FRAME = 64 * 1024;
    private static final String TEN_KIB = "x".repeat(10 * 1024);

    @Test
    void shouldStopReadingFromAPeerWhoseMessagesFillItsInboundBoundAndLoseNothing() throws Exception {
        var gate = new CountDownLatch(1);
        var received = new CopyOnWriteArrayList<Long>();
        long maxInbound = 2L * FRAME;
        try (var b = TestNode.start("b", TestNode.config().maxFrameBytes(FRAME).maxInboundBytesPerPeer(maxInbound));
             var a = TestNode.start("a", TestNode.config().maxFrameBytes(FRAME).peer(b.address()))) {
            b.node.add(SLOW, () -> (message, context) -> {
                assertTrue(gate.await(60, TimeUnit.SECONDS));
                received.add(Long.parseLong(message.contentsAs(Text.class).text().substring(0, 8).trim()));
            });
            assertTrue(a.net.awaitResolvable(SLOW, Duration.ofSeconds(30)));
            int count = 100; // 1 MiB in all, eight times the bound
            for (int i = 0; i < count; i++) {
                a.node.send(SLOW, new Text(String.format("%8d", i) + TEN_KIB), QoS.of(Criticality.MIDDLE));
            }
            Await.until("b pauses reading from a", () -> b.net.stats().inboundPauses() > 0);
            long heldBytes = b.node.queuedBytesFrom("a");
            assertTrue(heldBytes <= maxInbound, "b holds " + heldBytes + " bytes of a's, bound " + maxInbound);
            assertTrue(heldBytes > 0);

            gate.countDown();
            Await.until("every message arrived", () -> received.size() == count);
            for (int i = 0; i < count; i++) {
                assertEquals(i, received.get(i), "in order, none lost or twice");
            }
            assertEquals(0, a.net.stats().undeliverable(), a.net.stats().toString());
            assertEquals(0, b.node.queuedBytesFrom("a"));
        }
    }

    @Test
    void shouldKeepAtMostTheLowBudgetOfLowMessagesUnacknowledged() throws Exception {
        var gate = new CountDownLatch(1);
        var received = new CopyOnWriteArrayList<Long>();
        int frame = 256 * 1024;
        String sixtyFourKiB = "y".repeat(64 * 1024 - 16);
        // b holds at most two frames of a's messages, then stops reading: what a has written and b
        // has not acknowledged stays in flight, where a's LOW budget (128 KiB) must bound it. One
        // lane: with two, LOW never shares a connection with HIGH and needs no budget.
        try (var b = TestNode.start("b", TestNode.config().lanes(1).maxFrameBytes(frame)
                .maxInboundBytesPerPeer(2L * frame));
             var a = TestNode.start("a", TestNode.config().lanes(1).maxFrameBytes(frame).peer(b.address()))) {
            b.node.add(SLOW, () -> (message, context) -> {
                assertTrue(gate.await(60, TimeUnit.SECONDS));
                received.add(Long.parseLong(message.contentsAs(Text.class).text().substring(0, 8).trim()));
            });
            assertTrue(a.net.awaitResolvable(SLOW, Duration.ofSeconds(30)));
            int count = 40;
            int mostInFlight = 0;
            for (int i = 0; i < count; i++) {
                a.node.send(SLOW, new Text(String.format("%8d", i) + sixtyFourKiB), QoS.of(Criticality.LOW));
                mostInFlight = Math.max(mostInFlight, a.net.peer("b").orElseThrow().inFlight());
            }
            long untilNs = System.nanoTime() + TimeUnit.MILLISECONDS.toNanos(500);
            while (System.nanoTime() < untilNs) {
                mostInFlight = Math.max(mostInFlight, a.net.peer("b").orElseThrow().inFlight());
                Thread.sleep(1);
            }
            assertTrue(mostInFlight <= 2, "LOW messages of 64 KiB unacknowledged at once: " + mostInFlight);
            assertTrue(a.net.peer("b").orElseThrow().queued() > 0, "the rest wait in a's queue");

            gate.countDown();
            Await.until("every LOW message arrived", () -> received.size() == count);
            for (int i = 0; i < count; i++) {
                assertEquals(i, received.get(i), "in order, none lost or twice");
            }
        }
    }

    @Test
    void shouldShedOrRefuseMessagesBeyondTheBytesQueuedForAPeer() throws Exception {
        long maxQueued = 2L * FRAME;
        // b is never reachable: everything for it waits in a's queue.
        try (var a = TestNode.start("a", TestNode.config().maxFrameBytes(FRAME).maxQueuedBytesPerPeer(maxQueued)
                .peer(new InetSocketAddress("127.0.0.1", 1)))) {
            var toB = a.net.routeTo("b");
            int lowSent = 0;
            while (a.net.stats().overflowDropped() == 0 && lowSent < 1_000) {
                toB.deliver(message(a, Criticality.LOW));
                lowSent++;
            }
            assertTrue(lowSent * 10L * 1024 <= maxQueued + 20L * 1024,
                    "LOW shed once the bytes reached the bound: " + lowSent + " sent");
            int[] backlog = {a.net.peer("b").orElseThrow().queued()};
            assertTrue(backlog[0] < lowSent, "the queue holds fewer than were offered: " + backlog[0]);

            // HIGH evicts LOW to make room; once only HIGH waits, a HIGH one is refused, not queued.
            List<Exception> refusals = new CopyOnWriteArrayList<>();
            for (int i = 0; i < 2 * lowSent; i++) {
                try {
                    toB.deliver(message(a, Criticality.HIGH));
                } catch (IllegalStateException e) {
                    refusals.add(e);
                }
            }
            assertTrue(!refusals.isEmpty(), "HIGH messages beyond the bound are refused");
            assertTrue(refusals.getFirst().getMessage().contains("maxQueuedBytesPerPeer=" + maxQueued),
                    refusals.getFirst().getMessage());
        }
    }

    @Test
    void shouldRefuseAtTheSenderAMessageLargerThanThePeersCodecTakesAndKeepTheConnection() throws Exception {
        // b's codec takes 16 KiB documents, though its frames may be 64 KiB: b says so in its HELLO.
        int documentLimit = 16 * 1024;
        ContentsTypes bTypes = Num.register(new ContentsTypes());
        MessageCodec smallCodec = MessageCodec.builder().contentsTypes(bTypes).maxDocumentBytes(documentLimit).build();
        var received = new CopyOnWriteArrayList<String>();
        try (var b = TestNode.start("b", NodeClock.system(), TestNode.config().maxFrameBytes(FRAME).codec(smallCodec),
                node -> node.contentsTypes(bTypes));
             var a = TestNode.start("a", TestNode.config().maxFrameBytes(FRAME).peer(b.address()))) {
            b.node.add(SLOW, () -> (message, context) -> received.add(message.contentsAs(Text.class).text()));
            assertTrue(a.net.awaitResolvable(SLOW, Duration.ofSeconds(30)));
            long opened = a.net.stats().connectionsOpened();
            var toB = a.net.routeTo("b");

            // 20 KiB of text: within both nodes' frames and a's codec, over b's codec.
            MessageId large = a.node.newMessageId();
            var refused = assertThrows(IllegalStateException.class, () -> toB.deliver(new Message(SLOW, null, 0,
                    QoS.of(Criticality.HIGH), new Text("x".repeat(20 * 1024)), large, null)));
            assertTrue(refused.getMessage().contains("message " + large) && refused.getMessage().contains("node 'b'"),
                    refused.getMessage());
            toB.deliver(new Message(SLOW, null, 0, QoS.of(Criticality.HIGH), new Text("after"), a.node.newMessageId(),
                    null));

            Await.until("the next message arrived", () -> received.contains("after"));
            assertEquals(List.of("after"), received);
            assertEquals(opened, a.net.stats().connectionsOpened(), "no connection was replaced");
            for (TestNode node : List.of(a, b)) {
                assertEquals(0, node.net.stats().closes(CloseReason.MALFORMED_MESSAGE), node.net.stats().toString());
            }
        }
    }

    private static Message message(TestNode from, Criticality criticality) {
        MessageId id = from.node.newMessageId();
        return new Message(SLOW, null, 0, QoS.of(criticality), new Text(TEN_KIB), id, null);
    }

    @Test
    void shouldRefuseABoundBelowTwoFrames() {
        var e = assertThrows(IllegalArgumentException.class,
                () -> NetworkConfig.builder().maxFrameBytes(FRAME).maxQueuedBytesPerPeer(FRAME).build());
        assertTrue(e.getMessage().startsWith("maxQueuedBytesPerPeer=65536 must be in [131072"), e.getMessage());
    }
}
