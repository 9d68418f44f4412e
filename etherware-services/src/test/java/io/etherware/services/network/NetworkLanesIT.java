package io.etherware.services.network;

import static org.junit.jupiter.api.Assertions.assertEquals;
import static org.junit.jupiter.api.Assertions.assertFalse;
import static org.junit.jupiter.api.Assertions.assertThrows;
import static org.junit.jupiter.api.Assertions.assertTrue;

import io.etherware.core.message.Criticality;
import io.etherware.core.message.Profile;
import io.etherware.core.message.QoS;
import io.etherware.core.message.Text;
import io.etherware.core.time.NodeClock;
import io.etherware.rt.scheduling.RealtimeScheduler;
import io.etherware.rt.scheduling.RealtimeSchedulerConfig;
import io.etherware.rt.scheduling.ThreadSchedulingRule;
import io.etherware.testkit.Await;
import java.time.Duration;
import java.util.concurrent.CopyOnWriteArrayList;
import java.util.concurrent.CountDownLatch;
import java.util.concurrent.ExecutionException;
import java.util.concurrent.TimeUnit;
import org.junit.jupiter.api.Test;

/**
 * Priority on the wire: with two lanes a HIGH request and its reply cross the network while the
 * LOW lane to the same node is backed up (its receiver stopped reading at its inbound bound, the
 * sockets full of LOW bytes); with one lane the same request waits behind the LOW bytes. Ordinary
 * threads: the claim is about connections, not OS priorities.
 */
class NetworkLanesIT {

    private static final Profile ECHO = Profile.of("echo");
    private static final Profile SLOW = Profile.of("slow-sink");
    private static final int FRAME_BYTES = 64 * 1024;
    private static final int LOW_MESSAGES = 100;
    private static final String SIXTEEN_KIB = "z".repeat(16 * 1024);
    private static final QoS HIGH = QoS.of(Criticality.HIGH);

    @Test
    void shouldAnswerHighRequestsWhileTheLowLaneToTheSameNodeIsBackedUp() throws Exception {
        try (var pair = new BackedUpPair(2)) {
            for (int i = 0; i < 50; i++) {
                assertEquals(new Text("hi " + i), pair.a.node.request(ECHO, new Text("hi " + i), HIGH,
                        TimeUnit.SECONDS.toNanos(10)).get(20, TimeUnit.SECONDS).contents(),
                        "HIGH request " + i + " answered past the backed-up LOW lane");
            }
            assertTrue(pair.b.net.stats().inboundPauses() > 0, "the LOW lane was still held up");
            pair.releaseAndAwaitEveryLowMessage();
        }
    }

    @Test
    void shouldHoldHighBehindBackedUpLowBytesOnOneLane() throws Exception {
        try (var pair = new BackedUpPair(1)) {
            var error = assertThrows(ExecutionException.class, () -> pair.a.node.request(ECHO, new Text("stuck"), HIGH,
                    TimeUnit.MILLISECONDS.toNanos(500)).get(20, TimeUnit.SECONDS));
            assertTrue(String.valueOf(error.getCause()).contains("no reply from 'echo'"), String.valueOf(error.getCause()));
            pair.releaseAndAwaitEveryLowMessage();
        }
    }

    @Test
    void shouldRefuseAPeerThatRunsAnotherNumberOfLanes() throws Exception {
        try (var b = TestNode.start("b", TestNode.config());
             var a = TestNode.start("a", TestNode.config().lanes(1).peer(b.address()))) {
            Await.until("b refused a's single lane", () -> b.net.stats().closes(CloseReason.BAD_HANDSHAKE) > 0);
            assertFalse(a.net.awaitConnected("b", Duration.ofMillis(300)), "never connected");
            assertEquals(0, b.net.stats().connectionsOpened(), b.net.stats().toString());
        }
    }

    @Test
    void shouldSendANoneMessageOnlyAfterWhatLaneZeroHadQueuedBeforeIt() throws Exception {
        Profile sink = Profile.of("r-sink");
        try (var a = TestNode.start("a", TestNode.config());
             var bulk = new RawPeer(a.address())) {
            // Peer r connects its lane 1 only: a's lane 0 to r is down, so what a queues there waits.
            connectLaneOneOnly(bulk, a, sink);
            a.node.send(sink, new Text("first"), HIGH);
            a.node.send(sink, new Text("behind"), QoS.of(Criticality.NONE));

            assertTrue(dataWithin(bulk, 500) == null, "the NONE message waited for lane 0's HIGH one");

            try (var urgent = new RawPeer(a.address())) {
                urgent.hello(RawPeer.MAGIC, RawPeer.VERSION, "r", 0);
                urgent.expect(RawPeer.HELLO);
                urgent.expect(RawPeer.RESUME);
                urgent.resume(8, 0, 0);
                RawPeer.Received first = dataWithin(urgent, 10_000);
                assertTrue(first != null && RawPeer.dataXml(first).contains("first"), "lane 0 brought the HIGH one");
                assertTrue(dataWithin(bulk, 300) == null, "still waiting: r has not acknowledged it");
                urgent.ack(1);
                RawPeer.Received behind = dataWithin(bulk, 10_000);
                assertTrue(behind != null && RawPeer.dataXml(behind).contains("behind"),
                        "the NONE message went once lane 0's was acknowledged");
            }
        }
    }

    @Test
    void shouldGiveUpALaneThatStaysDownWhileTheOtherIsUp() throws Exception {
        Profile sink = Profile.of("r-sink");
        try (var a = TestNode.start("a", TestNode.config().peerDownGrace(Duration.ofMillis(1500)));
             var bulk = new RawPeer(a.address())) {
            connectLaneOneOnly(bulk, a, sink);
            long startNs = System.nanoTime();
            var request = a.node.request(sink, new Text("never answered"), HIGH, TimeUnit.SECONDS.toNanos(20));
            var error = assertThrows(ExecutionException.class, () -> request.get(30, TimeUnit.SECONDS));
            assertTrue(System.nanoTime() - startNs < TimeUnit.SECONDS.toNanos(12),
                    "its sender heard of it after the grace period (1.5 s), not at its own timeout (20 s): "
                            + error.getCause());
            a.node.send(sink, new Text("behind"), QoS.of(Criticality.NONE));
            RawPeer.Received behind = dataWithin(bulk, 10_000);
            assertTrue(behind != null && RawPeer.dataXml(behind).contains("behind"),
                    "a NONE message no longer waits for the lane given up");
        }
    }

    /** Peer r connects only its lane 1 to {@code a} and announces {@code sink}. */
    private static void connectLaneOneOnly(RawPeer bulk, TestNode a, Profile sink) throws Exception {
        bulk.hello(RawPeer.MAGIC, RawPeer.VERSION, "r", 1);
        bulk.expect(RawPeer.HELLO);
        bulk.expect(RawPeer.RESUME);
        bulk.resume(7, 0, 0);
        bulk.announce(0, "etherware.node[id=r]", sink.toString());
        assertTrue(a.net.awaitResolvable(sink, Duration.ofSeconds(30)));
    }

    /** The first DATA frame {@code peer} reads within {@code ms}, or null. */
    private static RawPeer.Received dataWithin(RawPeer peer, long ms) throws java.io.IOException {
        long endNs = System.nanoTime() + TimeUnit.MILLISECONDS.toNanos(ms);
        while (true) {
            long leftMs = TimeUnit.NANOSECONDS.toMillis(endNs - System.nanoTime());
            if (leftMs <= 0) {
                return null;
            }
            peer.soTimeoutMs((int) leftMs);
            try {
                RawPeer.Received frame = peer.read();
                if (frame.type() == RawPeer.DATA) {
                    return frame;
                }
            } catch (java.net.SocketTimeoutException e) {
                return null;
            }
        }
    }

    /**
     * Node a floods LOW messages to a sink on node b that holds them all; b stops reading a's LOW
     * messages at its inbound bound, and TCP backs the rest up to a. Node b has an echo (HIGH).
     */
    private static final class BackedUpPair implements AutoCloseable {
        final TestNode b;
        final TestNode a;
        final CountDownLatch gate = new CountDownLatch(1);
        final CopyOnWriteArrayList<Integer> received = new CopyOnWriteArrayList<>();

        BackedUpPair(int lanes) throws Exception {
            // Table II's dispatchers without OS priorities: the sink holds only the LOW dispatcher.
            var scheduler = new RealtimeScheduler(RealtimeSchedulerConfig.builder().name("b-lanes")
                    .threadSchedulingRule(ThreadSchedulingRule.tableII().withoutRealtime()).build());
            b = TestNode.start("b", NodeClock.system(), TestNode.config().lanes(lanes).maxFrameBytes(FRAME_BYTES)
                    .maxInboundBytesPerPeer(2L * FRAME_BYTES), settings -> settings.scheduler(() -> scheduler));
            TestNode started = null;
            try {
                started = TestNode.start("a", TestNode.config().lanes(lanes).maxFrameBytes(FRAME_BYTES)
                        .peer(b.address()));
                b.node.add(ECHO, () -> (message, context) -> context.reply(message, message.contents()));
                b.node.add(SLOW, () -> (message, context) -> {
                    assertTrue(gate.await(60, TimeUnit.SECONDS));
                    received.add(Integer.parseInt(message.contentsAs(Text.class).text().substring(0, 8).trim()));
                });
                assertTrue(started.net.awaitResolvable(ECHO, Duration.ofSeconds(30)));
                assertTrue(started.net.awaitResolvable(SLOW, Duration.ofSeconds(30)));
                for (int i = 0; i < LOW_MESSAGES; i++) {
                    started.node.send(SLOW, new Text(String.format("%8d", i) + SIXTEEN_KIB), QoS.of(Criticality.LOW));
                }
                Await.until("b stopped reading a's LOW messages", () -> b.net.stats().inboundPauses() > 0);
            } catch (Exception | Error e) {
                if (started != null) {
                    started.close();
                }
                b.close();
                throw e;
            }
            a = started;
        }

        /** Nothing of the LOW flood was lost, reordered or doubled. */
        void releaseAndAwaitEveryLowMessage() {
            gate.countDown();
            Await.until("every LOW message arrived", () -> received.size() == LOW_MESSAGES);
            for (int i = 0; i < LOW_MESSAGES; i++) {
                assertEquals(i, received.get(i), "in order, none lost or twice");
            }
        }

        @Override
        public void close() {
            gate.countDown();
            a.close();
            b.close();
        }
    }
}
