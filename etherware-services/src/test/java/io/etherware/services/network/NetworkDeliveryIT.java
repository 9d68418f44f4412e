package io.etherware.services.network;

import static org.junit.jupiter.api.Assertions.assertEquals;
import static org.junit.jupiter.api.Assertions.assertFalse;
import static org.junit.jupiter.api.Assertions.assertInstanceOf;
import static org.junit.jupiter.api.Assertions.assertThrows;
import static org.junit.jupiter.api.Assertions.assertTrue;

import io.etherware.core.component.Component;
import io.etherware.core.component.RequestFailedException;
import io.etherware.core.kernel.Undeliverable;
import io.etherware.core.message.Criticality;
import io.etherware.core.message.Message;
import io.etherware.core.message.MessageId;
import io.etherware.core.message.Profile;
import io.etherware.core.message.QoS;
import io.etherware.core.message.Text;
import io.etherware.testkit.Await;
import java.net.InetSocketAddress;
import java.time.Duration;
import java.util.Set;
import java.util.concurrent.ConcurrentHashMap;
import java.util.concurrent.ExecutionException;
import java.util.concurrent.TimeUnit;
import java.util.concurrent.atomic.AtomicLong;
import java.util.function.Supplier;
import org.junit.jupiter.api.Test;

/**
 * Nothing is lost silently: bulk order, reconnection with the peer alive (exactly once),
 * a peer killed and brought back, a peer that stays away, a congested peer.
 */
class NetworkDeliveryIT {

    private static final Profile SINK = Profile.of("sink");
    private static final Profile PUMP = Profile.of("pump");
    private static final QoS HIGH = QoS.of(Criticality.HIGH);

    /** Counts arrivals in order, by value: any value other than the next is out of order. */
    private static final class OrderedSink {
        final AtomicLong received = new AtomicLong();
        final AtomicLong outOfOrder = new AtomicLong();

        Supplier<Component> factory() {
            return () -> (message, context) -> {
                if (message.contentsAs(Num.class).value() != received.get()) {
                    outOfOrder.incrementAndGet();
                }
                received.incrementAndGet();
            };
        }
    }

    /**
     * A component that sends a HIGH message to the sink for each Num it gets, and records the
     * ids it sent and the undeliverable notices that come back for them.
     */
    private static final class Pump {
        final Set<MessageId> sent = ConcurrentHashMap.newKeySet();
        final Set<MessageId> noticed = ConcurrentHashMap.newKeySet();

        Supplier<Component> factory() {
            return () -> (message, context) -> {
                if (message.contents() instanceof Undeliverable) {
                    noticed.add(message.correlationId());
                } else {
                    sent.add(context.send(SINK, message.contents(), HIGH));
                }
            };
        }
    }

    /** Records the ids of arrivals; an id arriving twice is a duplicate. */
    private static final class IdSink {
        final Set<MessageId> received = ConcurrentHashMap.newKeySet();
        final AtomicLong duplicates = new AtomicLong();

        Supplier<Component> factory() {
            return () -> (message, context) -> {
                if (!received.add(message.messageId())) {
                    duplicates.incrementAndGet();
                }
            };
        }
    }

    @Test
    void shouldDeliverOneHundredThousandMessagesInOrderWithNoneLost() throws Exception {
        int count = 100_000;
        var sink = new OrderedSink();
        try (var b = TestNode.start("b", TestNode.config());
             var a = TestNode.start("a", TestNode.config().peer(b.address()).queueCapacity(count))) {
            b.node.add(SINK, sink.factory());
            assertTrue(a.net.awaitResolvable(SINK, Duration.ofSeconds(30)));
            for (int i = 0; i < count; i++) {
                a.node.send(SINK, new Num(i));
            }
            Await.until("100,000 messages arrive", 180_000, () -> sink.received.get() == count);
            assertEquals(0, sink.outOfOrder.get());
            // The counters count after the hand-off (the writer after its flush, the reader after the
            // kernel took the message), so the sink can see the last message before they move.
            Await.until("the counters count every message", 10_000, () -> a.net.stats().messagesSent() >= count
                    && b.net.stats().messagesReceived() >= count);
            assertEquals(count, a.net.stats().messagesSent());
            assertEquals(count, b.net.stats().messagesReceived());
            assertEquals(0, a.net.stats().overflowDropped());
            assertEquals(0, a.net.stats().undeliverable());
        }
    }

    @Test
    void shouldResumeWithoutLossOrDuplicatesWhenTheConnectionIsCutWhileBothNodesLive() throws Exception {
        int count = 20_000;
        var sink = new OrderedSink();
        try (var b = TestNode.start("b", TestNode.config());
             var proxy = new LoopbackProxy(b.address());
             var a = TestNode.start("a", TestNode.config().peer(proxy.address()).queueCapacity(count))) {
            b.node.add(SINK, sink.factory());
            assertTrue(a.net.awaitResolvable(SINK, Duration.ofSeconds(30)));
            for (int i = 0; i < count; i++) {
                a.node.send(SINK, new Num(i));
                if (i % 5_000 == 2_500) {
                    proxy.cut();
                }
            }
            Await.until("all messages arrive despite the cuts", 120_000, () -> sink.received.get() == count);
            assertEquals(0, sink.outOfOrder.get(), "in order, none twice");
            assertTrue(a.net.stats().connectionsOpened() > TestNode.LANES, "a reconnected: " + a.net.stats());
            assertEquals(0, a.net.stats().undeliverable());
            assertEquals(0, b.net.stats().badInputCloses(), "resent before anything newer: " + b.net.stats());
            // Nothing arrives after the count: no duplicate was delivered late.
            Thread.sleep(200);
            assertEquals(count, sink.received.get());
        }
    }

    @Test
    void shouldDeliverOrReportEveryHighMessageWhenAPeerIsKilledAndBroughtBack() throws Exception {
        var pump = new Pump();
        var sink = new IdSink();
        int count = 1_500;
        TestNode b = TestNode.start("b", TestNode.config());
        int port = b.address().getPort();
        b.node.add(SINK, sink.factory());
        // Through a proxy, so that b can die without a word: a clean close says BYE SHUTDOWN, which
        // unroutes b's profiles at once, where a crash leaves them for the grace period.
        try (var proxy = new LoopbackProxy(b.address());
             var a = TestNode.start("a", TestNode.config().peer(proxy.address()).peerDownGrace(Duration.ofSeconds(60)))) {
            a.node.add(PUMP, pump.factory());
            assertTrue(a.net.awaitResolvable(SINK, Duration.ofSeconds(30)));
            TestNode restarted = null;
            try {
                for (int i = 0; i < count; i++) {
                    a.node.send(PUMP, new Num(i));
                    Thread.sleep(0, 500_000);
                    if (i == 300) {
                        proxy.stall(true); // b's last words never reach a
                        b.close();
                        proxy.cut();
                        proxy.stall(false);
                        Await.until("a notices b is gone", () -> !a.net.peer("b").orElseThrow().connected());
                    }
                    if (i == 900) {
                        restarted = TestNode.start("b", TestNode.config()
                                .listen(new InetSocketAddress("127.0.0.1", port)));
                        restarted.node.add(SINK, sink.factory());
                    }
                }
                Await.until("every message arrived or was reported",
                        () -> pump.sent.size() == count && accounted(pump, sink) == count);
                assertEquals(0, sink.duplicates.get());
                assertTrue(sink.received.size() > 900, "messages queued while b was down arrived: "
                        + sink.received.size());
                assertEquals(pump.noticed.size(), a.net.stats().undeliverable());
            } finally {
                if (restarted != null) {
                    restarted.close();
                }
            }
        }
    }

    private static long accounted(Pump pump, IdSink sink) {
        return pump.sent.stream().filter(id -> sink.received.contains(id) || pump.noticed.contains(id)).count();
    }

    @Test
    void shouldReportUnacknowledgedMessagesWhenAPeerDiesAbruptlyAndRestarts() throws Exception {
        var pump = new Pump();
        var sink = new IdSink();
        int count = 400;
        TestNode b = TestNode.start("b", TestNode.config());
        int port = b.address().getPort();
        b.node.add(SINK, sink.factory());
        try (var proxy = new LoopbackProxy(b.address());
             var a = TestNode.start("a", TestNode.config().peer(proxy.address()))) {
            a.node.add(PUMP, pump.factory());
            assertTrue(a.net.awaitResolvable(SINK, Duration.ofSeconds(30)));
            for (int i = 0; i < count / 2; i++) {
                a.node.send(PUMP, new Num(i));
            }
            Await.until("the first half arrives", () -> sink.received.size() == count / 2);
            // The path hangs, a writes on into it, then b dies without a word reaching a.
            proxy.stall(true);
            for (int i = count / 2; i < count; i++) {
                a.node.send(PUMP, new Num(i));
            }
            Await.until("a has written everything", () -> pump.sent.size() == count
                    && a.net.peer("b").orElseThrow().queued() == 0);
            proxy.cut();
            b.close();
            proxy.stall(false);
            try (var restarted = TestNode.start("b", TestNode.config().listen(new InetSocketAddress("127.0.0.1", port)))) {
                restarted.node.add(SINK, sink.factory());
                Await.until("every message arrived or was reported", () -> accounted(pump, sink) == count);
                assertFalse(pump.noticed.isEmpty(), "messages of unknown fate are reported");
                assertEquals(0, sink.duplicates.get());
            }
        }
    }

    @Test
    void shouldCloseASilentConnectionAtTheHeartbeatTimeoutAndResumeWithNothingLost() throws Exception {
        var pump = new Pump();
        var sink = new IdSink();
        int count = 200;
        try (var b = TestNode.start("b", TestNode.config());
             var proxy = new LoopbackProxy(b.address());
             var a = TestNode.start("a", TestNode.config().peer(proxy.address())
                     .heartbeatInterval(Duration.ofMillis(100)).heartbeatTimeout(Duration.ofMillis(400)))) {
            b.node.add(SINK, sink.factory());
            a.node.add(PUMP, pump.factory());
            assertTrue(a.net.awaitResolvable(SINK, Duration.ofSeconds(30)));
            // The path goes silent without closing (a pulled cable, a hung switch): only the
            // heartbeat can tell, and a must not wait for TCP's own timeouts of many minutes.
            proxy.stall(true);
            for (int i = 0; i < count; i++) {
                a.node.send(PUMP, new Num(i));
            }
            Await.until("a closes the silent connection", () -> a.net.stats().closes(CloseReason.HEARTBEAT_TIMEOUT) > 0);
            assertEquals(0, a.net.stats().closes(CloseReason.PEER_CLOSED), "closed for silence, not by the peer");
            proxy.stall(false);
            Await.until("every message arrived or was reported", () -> pump.sent.size() == count
                    && accounted(pump, sink) == count);
            assertEquals(0, sink.duplicates.get());
            b.node.add(Profile.of("echo"), () -> (message, context) -> context.reply(message, message.contents()));
            assertTrue(a.net.awaitResolvable(Profile.of("echo"), Duration.ofSeconds(30)), "announcements flow again");
            assertEquals(new Text("back"), a.node.requestBlocking(Profile.of("echo"), new Text("back")).contents());
        }
    }

    @Test
    void shouldFailARequestAsUndeliverableWhenThePeerStaysDownPastTheGrace() throws Exception {
        TestNode b = TestNode.start("b", TestNode.config());
        b.node.add(Profile.of("echo"), () -> (message, context) -> context.reply(message, message.contents()));
        try (var a = TestNode.start("a", TestNode.config().peer(b.address()).peerDownGrace(Duration.ofMillis(500)))) {
            assertTrue(a.net.awaitResolvable(Profile.of("echo"), Duration.ofSeconds(30)));
            b.close();
            Await.until("a notices b is gone", () -> !a.net.peer("b").orElseThrow().connected());
            long startNs = System.nanoTime();
            var error = assertThrows(ExecutionException.class, () -> a.node.request(Profile.of("echo"), new Text("?"),
                    HIGH, TimeUnit.SECONDS.toNanos(60)).get(60, TimeUnit.SECONDS));
            var failure = assertInstanceOf(RequestFailedException.class, error.getCause());
            assertEquals(RequestFailedException.Reason.UNDELIVERABLE, failure.reason(), failure.getMessage());
            assertTrue(System.nanoTime() - startNs < TimeUnit.SECONDS.toNanos(30), "reported at the grace, not the timeout");
            Await.until("b's profiles are unrouted", () -> !a.node.registry().profiles().contains(Profile.of("echo")));
        }
    }

    @Test
    void shouldKeepOtherPeersAndLocalDeliveryGoingWhileOnePeerIsCongested() throws Exception {
        var pump = new Pump();
        var sink = new IdSink();
        try (var b = TestNode.start("b", TestNode.config());
             var c = TestNode.start("c", TestNode.config());
             var proxy = new LoopbackProxy(b.address());
             var a = TestNode.start("a", TestNode.config().peer(proxy.address()).peer(c.address())
                     .queueCapacity(500).windowMessages(100))) {
            b.node.add(SINK, sink.factory());
            c.node.add(Profile.of("echo"), () -> (message, context) -> context.reply(message, message.contents()));
            a.node.add(PUMP, pump.factory());
            assertTrue(a.net.awaitResolvable(SINK, Duration.ofSeconds(30)));
            assertTrue(a.net.awaitResolvable(Profile.of("echo"), Duration.ofSeconds(30)));
            proxy.stall(true);
            long startNs = System.nanoTime();
            for (int i = 0; i < 20_000; i++) {
                a.node.send(SINK, new Num(i), QoS.of(Criticality.LOW));
            }
            for (int i = 0; i < 2_000; i++) {
                a.node.send(PUMP, new Num(i));
            }
            long sendingMs = TimeUnit.NANOSECONDS.toMillis(System.nanoTime() - startNs);
            // While b's path is hung: c answers, and a's own components run.
            assertEquals(new Text("still here"), a.node.requestBlocking(Profile.of("echo"), new Text("still here"))
                    .contents());
            Await.until("the pump sent all", () -> pump.sent.size() == 2_000);
            assertTrue(a.net.stats().overflowDropped() > 0, "LOW messages were shed: " + a.net.stats());
            // The refusals come back to the pump as notices, queued behind its own work: wait for them.
            Await.until("HIGH messages refused by the full queue are reported", () -> !pump.noticed.isEmpty());
            proxy.stall(false);
            Await.until("every HIGH message arrived or was reported", () -> accounted(pump, sink) == 2_000);
            assertTrue(sendingMs < 20_000, "senders never waited for the hung peer: " + sendingMs + " ms");
        }
    }

    @Test
    void shouldRefuseAMessageRelayedMoreThanMaxHops() throws Exception {
        // b routes 'loop' to a and a routes it to b: stale routes of a migration gone wrong.
        try (var b = TestNode.start("b", TestNode.config());
             var a = TestNode.start("a", TestNode.config().peer(b.address()).maxHops(3))) {
            assertTrue(a.net.awaitConnected("b", Duration.ofSeconds(30)));
            assertTrue(b.net.awaitConnected("a", Duration.ofSeconds(30)));
            a.node.registry().registerRemote(Profile.of("loop"), a.net.routeTo("b"));
            b.node.registry().registerRemote(Profile.of("loop"), b.net.routeTo("a"));
            var error = assertThrows(ExecutionException.class, () -> a.node.request(Profile.of("loop"), new Text("?"),
                    HIGH, TimeUnit.SECONDS.toNanos(60)).get(60, TimeUnit.SECONDS));
            var failure = assertInstanceOf(RequestFailedException.class, error.getCause());
            assertEquals(RequestFailedException.Reason.UNDELIVERABLE, failure.reason());
            assertTrue(failure.getMessage().contains("relayed"), failure.getMessage());
        }
    }

    @Test
    void shouldTellTheSenderWhenAMessageDoesNotEncode() throws Exception {
        record Unregistered(String text) implements io.etherware.core.message.Contents {
        }
        var notices = new java.util.concurrent.LinkedBlockingQueue<Message>();
        try (var b = TestNode.start("b", TestNode.config());
             var a = TestNode.start("a", TestNode.config().peer(b.address()))) {
            b.node.add(SINK, () -> (message, context) -> { });
            a.node.add(PUMP, () -> (message, context) -> {
                if (message.contents() instanceof Undeliverable) {
                    notices.add(message);
                } else {
                    context.send(SINK, new Unregistered("not on the wire"));
                }
            });
            assertTrue(a.net.awaitResolvable(SINK, Duration.ofSeconds(30)));
            a.node.send(PUMP, new Num(1));
            var notice = notices.poll(30, TimeUnit.SECONDS);
            var undeliverable = assertInstanceOf(Undeliverable.class, notice.contents());
            assertTrue(undeliverable.reason().contains("does not encode"), undeliverable.reason());
            assertTrue(a.net.awaitConnected("b", Duration.ofSeconds(1)), "the connection stays up");
        }
    }
}
