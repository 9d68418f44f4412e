package io.etherware.services.network;

import static io.etherware.services.network.HostileKit.ECHO;
import static io.etherware.services.network.HostileKit.LEGIT_TIMEOUT_MS;
import static io.etherware.services.network.HostileKit.nodeProfile;
import static org.junit.jupiter.api.Assertions.assertEquals;
import static org.junit.jupiter.api.Assertions.assertFalse;
import static org.junit.jupiter.api.Assertions.assertTrue;

import io.etherware.core.message.MessageId;
import io.etherware.core.message.Text;
import io.etherware.testkit.Await;
import java.io.IOException;
import java.net.Socket;
import java.nio.ByteBuffer;
import java.nio.charset.StandardCharsets;
import java.time.Duration;
import java.util.ArrayList;
import java.util.List;
import java.util.concurrent.TimeUnit;
import org.junit.jupiter.api.AfterEach;
import org.junit.jupiter.api.Test;

/**
 * Hostile peers against the node's resources, over plain TCP on loopback: a peer that sends large
 * requests and never reads the replies, floods of connections that never complete a handshake,
 * and first frames that cannot be a HELLO. Meanwhile node {@code legit} requests the
 * {@code echo} component of node {@code target} every 10 ms and loses nothing; the target's heap
 * stays bounded.
 */
class HostileFloodIT {

    private static final long MiB = 1 << 20;

    private TestNode target;
    private TestNode legit;
    private LegitLoad load;
    private String legitConnection;
    private final List<TestNode> honest = new ArrayList<>();
    private final List<Socket> flood = new java.util.concurrent.CopyOnWriteArrayList<>();

    /** Short heartbeats, so a peer that reads nothing is found out quickly. */
    private static NetworkConfig.Builder quick() {
        return TestNode.config().heartbeatInterval(Duration.ofMillis(100)).heartbeatTimeout(Duration.ofMillis(500));
    }

    private void startTheLegitimateTraffic(NetworkConfig.Builder targetConfig) throws Exception {
        target = TestNode.start("target", targetConfig);
        target.node.add(ECHO, HostileKit.echo());
        // The legitimate peer beats as often as the target expects, but gives the target 3 s
        // before it calls it dead: a target busy with a hog's 300 KiB frames on two loaded cores
        // may fall silent for half a second, and that is not what these tests are about.
        legit = TestNode.start("legit", quick().heartbeatTimeout(Duration.ofSeconds(3)).peer(target.address()));
        assertTrue(legit.net.awaitResolvable(ECHO, Duration.ofSeconds(30)));
        load = LegitLoad.start(legit.node, ECHO, LEGIT_TIMEOUT_MS);
        Await.until("the legitimate requests flow", () -> load.answered() >= 20);
        legitConnection = target.net.peer("legit").orElseThrow().remote().orElseThrow();
    }

    @AfterEach
    void stop() {
        for (Socket socket : flood) {
            closeQuietly(socket);
        }
        honest.forEach(TestNode::close);
        if (load != null) {
            load.close();
        }
        if (legit != null) {
            legit.close();
        }
        if (target != null) {
            target.close();
        }
    }

    private void assertTheLegitPeerLostNothing() throws InterruptedException {
        Thread.sleep(200);
        load.stop();
        assertEquals(0, load.failures().size(), load.toString());
        assertEquals(load.sent(), load.answered(), load.toString());
        assertEquals(legitConnection, target.net.peer("legit").orElseThrow().remote().orElse("none"),
                "the legitimate connection is the one from the start: " + target.net.stats());
    }

    /** Connects a raw peer as {@code nodeId} that announces its node profile, so echoes come back to it. */
    private RawPeer hog(String nodeId) throws IOException {
        var hog = new RawPeer(target.address());
        RawPeer.Resume node = hog.introduce(nodeId);
        hog.resume(1, node.streamId(), 0);
        assertEquals(RawPeer.ANNOUNCE, hog.read().type());
        hog.announce(1, nodeProfile(nodeId).toString());
        return hog;
    }

    /** A request of 300 KiB of text to the echo; the same document serves for every frame. */
    private static byte[] largeRequest(String nodeId) {
        return HostileKit.xml(ECHO, nodeProfile(nodeId), new Text("x".repeat(300 * 1024)),
                new MessageId(nodeId, 0), null);
    }

    @Test
    void shouldCloseAPeerThatSendsLargeRequestsAndNeverReadsTheRepliesWithTheHeapBounded() throws Exception {
        // Frames of 512 KiB and the queue bound at its minimum, 1 MiB: the burst's replies are
        // seven times that. A heartbeat timeout of 2 s: the target has read the burst long before.
        startTheLegitimateTraffic(TestNode.config().heartbeatInterval(Duration.ofMillis(200))
                .heartbeatTimeout(Duration.ofSeconds(2)).maxFrameBytes(512 * 1024).maxQueuedBytesPerPeer(MiB)
                .peerDownGrace(Duration.ofSeconds(2)));
        int burst = 24; // 7.2 MiB of requests, back to back
        byte[] request = largeRequest("hog");
        try (var watch = new HostileKit.UncaughtWatch()) {
            long heapBefore = HostileKit.usedHeapAfterGc();
            try (var hog = hog("hog")) {
                // From here on the hog reads nothing: replies pile up in the sockets and queues.
                for (int seq = 0; seq < burst; seq++) {
                    hog.data(seq, 0, 0, request);
                }
                // Then it stays alive with heartbeats (bounded in time): only not reading gives it away.
                long deadlineNs = System.nanoTime() + TimeUnit.SECONDS.toNanos(10);
                try {
                    while (target.net.stats().closes(CloseReason.NOT_READING) == 0
                            && System.nanoTime() < deadlineNs) {
                        hog.heartbeat();
                        Thread.sleep(100);
                    }
                } catch (IOException closed) {
                    // The target closed the hog: what the test waits for below.
                }
                // A few heartbeat timeouts: a margin, not a timing.
                Await.until("the target closed the hog for not reading", 10_000,
                        () -> target.net.stats().closes(CloseReason.NOT_READING) == 1);
                long heapWhileHeld = HostileKit.usedHeapAfterGc() - heapBefore;
                assertTrue(heapWhileHeld < 64 * MiB, "heap grew " + heapWhileHeld / MiB + " MiB");
            }
            // Refused at the route, so the kernel counts them (and tells the echo).
            assertTrue(target.node.stats().undeliverable() > 0, "replies beyond the byte bound were refused: "
                    + target.node.stats());
            Await.until("the hog's waiting replies are given up", () -> target.net.peer("hog").isEmpty());
            long heapAfter = HostileKit.usedHeapAfterGc() - heapBefore;
            assertTrue(heapAfter < 16 * MiB, "heap grew " + heapAfter / MiB + " MiB and stayed");
            assertFalse(watch.sawOutOfMemory(), watch.escaped.toString());
        }
        assertEquals(0, target.net.stats().closes(CloseReason.HEARTBEAT_TIMEOUT), target.net.stats().toString());
        assertTheLegitPeerLostNothing();
    }

    /**
     * Hogs that keep sending large requests back to back until they are closed, so the target's
     * reader is busy with their frames when the target gives up on them. Whether the reader is
     * inside a read at that moment is a race; five hogs in a row make losing it near certain.
     */
    @Test
    void shouldCloseEveryPeerThatNeverReadsWhileItKeepsTheReaderBusy() throws Exception {
        startTheLegitimateTraffic(quick().maxQueuedBytesPerPeer(2 * MiB));
        int hogs = 5;
        int most = 5_000; // bounded by the 10 s deadline too; the target closes it long before either
        for (int round = 0; round < hogs; round++) {
            String nodeId = "hog-" + round;
            byte[] request = largeRequest(nodeId);
            int written = 0;
            try (var hog = hog(nodeId)) {
                long deadlineNs = System.nanoTime() + TimeUnit.SECONDS.toNanos(10);
                try {
                    while (written < most && System.nanoTime() < deadlineNs) {
                        hog.data(written, 0, 0, request);
                        written++;
                    }
                } catch (IOException closed) {
                    // The target closed the hog's connection.
                }
            }
            int closed = round + 1;
            Await.until(nodeId + " counted as not reading", 5_000,
                    () -> target.net.stats().closes(CloseReason.NOT_READING) == closed);
            Await.until(nodeId + " no longer connected", 5_000,
                    () -> !target.net.peer(nodeId).map(PeerStatus::connected).orElse(false));
            assertTrue(written < most, nodeId + " was stopped: " + written + " requests");
        }
        assertTheLegitPeerLostNothing();
    }

    @Test
    void shouldLetHonestNodesJoinThroughAFloodOfConnectionsThatNeverCompleteTheirHandshake() throws Exception {
        startTheLegitimateTraffic(quick().handshakeTimeout(Duration.ofSeconds(2)).maxPendingHandshakes(16));
        int idle = 200;
        int truncated = 200;
        byte[] truncatedHello = java.util.Arrays.copyOf(hello("flood"), 12);
        // 100 connections a second for 4 s, twice the handshake timeout: a node that let pending
        // handshakes take its connection slots until they time out would lock the honest nodes
        // out for as long as the flood goes on.
        Thread flooding = Thread.ofPlatform().name("flood").start(() -> {
            try {
                for (int i = 0; i < idle + truncated; i++) {
                    var socket = new Socket();
                    flood.add(socket);
                    socket.connect(target.address(), 10_000);
                    if (i % 2 == 1) {
                        socket.getOutputStream().write(truncatedHello);
                    }
                    if (i % 10 == 9) {
                        Thread.sleep(100);
                    }
                }
            } catch (IOException | InterruptedException e) {
                throw new AssertionError("the flood stopped", e);
            }
        });
        Await.until("the flood is under way", () -> flood.size() >= 40);
        var starting = new ArrayList<java.util.concurrent.CompletableFuture<TestNode>>();
        for (int i = 0; i < 7; i++) {
            String nodeId = "honest-" + i;
            starting.add(java.util.concurrent.CompletableFuture.supplyAsync(() ->
                    TestNode.start(nodeId, quick().peer(target.address()))));
        }
        for (var node : starting) {
            honest.add(node.get(30, TimeUnit.SECONDS));
        }
        for (TestNode node : honest) {
            assertTrue(node.net.awaitResolvable(ECHO, Duration.ofSeconds(30)), node.node.nodeId() + " joined");
        }
        assertTrue(flooding.isAlive(), "all honest nodes joined while the flood went on: " + flood.size()
                + " flood connections so far");
        for (TestNode node : honest) {
            assertEquals(new Text("in"), node.node.requestBlocking(ECHO, new Text("in")).contents());
        }
        flooding.join(30_000);
        assertEquals(idle + truncated, flood.size(), "the flood was sent");
        Await.until("every flood connection was pushed out or timed out", () ->
                target.net.stats().closes(CloseReason.HANDSHAKE_EVICTED)
                        + target.net.stats().closes(CloseReason.HANDSHAKE_TIMEOUT) >= idle + truncated);
        // Pushed out, all but those still pending when the flood stopped (and a few, if the box stalls).
        assertTrue(target.net.stats().closes(CloseReason.HANDSHAKE_EVICTED) >= idle + truncated - 2 * 16,
                target.net.stats().toString());
        assertEquals(1 + honest.size(), target.net.stats().connectedPeers(), target.net.stats().toString());
        assertTheLegitPeerLostNothing();
    }

    @Test
    void shouldCloseAFirstFrameThatCannotBeAHelloAtOnce() throws Exception {
        startTheLegitimateTraffic(quick().handshakeTimeout(Duration.ofSeconds(10)));
        List<byte[]> lengths = List.of(new byte[] {0, 0, 0, 0}, new byte[] {0x7f, -1, -1, -1},
                ByteBuffer.allocate(4).putInt(1025).array());
        for (byte[] length : lengths) {
            try (var attacker = new RawPeer(target.address())) {
                long startNs = System.nanoTime();
                attacker.raw(length);
                List<RawPeer.Received> frames = attacker.readUntilClosed();
                long tookMs = TimeUnit.NANOSECONDS.toMillis(System.nanoTime() - startNs);
                // 10 s handshake timeout: closed within 1 s means closed at the length, not the timeout.
                assertTrue(tookMs < 1_000, "closed after " + tookMs + " ms");
                RawPeer.Received bye = frames.stream().filter(frame -> frame.type() == RawPeer.BYE).findFirst()
                        .orElseThrow();
                assertEquals(CloseReason.BAD_HANDSHAKE.code(), bye.byeCode(), bye.byeText());
            }
        }
        Await.until("all three counted", () -> target.net.stats().closes(CloseReason.BAD_HANDSHAKE) == 3);
        assertTheLegitPeerLostNothing();
    }

    /** A complete HELLO frame as {@code nodeId}. */
    private static byte[] hello(String nodeId) {
        byte[] id = nodeId.getBytes(StandardCharsets.UTF_8);
        int length = 1 + 4 + 2 + 2 + id.length + 8 + 8 + 4 + 1 + 1;
        return ByteBuffer.allocate(4 + length).putInt(length).put(RawPeer.HELLO).putInt(RawPeer.MAGIC)
                .putShort((short) RawPeer.VERSION).putShort((short) id.length).put(id).putLong(1).putLong(0)
                .putInt(1 << 20).put((byte) 2).put((byte) 0).array();
    }

    private static void closeQuietly(Socket socket) {
        try {
            socket.close();
        } catch (IOException e) {
            // Closing anyway.
        }
    }
}
