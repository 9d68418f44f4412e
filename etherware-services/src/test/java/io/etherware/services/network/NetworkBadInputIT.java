package io.etherware.services.network;

import static org.junit.jupiter.api.Assertions.assertEquals;
import static org.junit.jupiter.api.Assertions.assertTrue;

import io.etherware.core.codec.MessageCodec;
import io.etherware.core.message.Message;
import io.etherware.core.message.MessageId;
import io.etherware.core.message.Profile;
import io.etherware.core.message.QoS;
import io.etherware.core.message.Text;
import io.etherware.testkit.Await;
import java.nio.charset.StandardCharsets;
import java.time.Duration;
import java.util.List;
import java.util.Random;
import java.util.concurrent.LinkedBlockingQueue;
import java.util.concurrent.TimeUnit;
import org.junit.jupiter.api.AfterEach;
import org.junit.jupiter.api.BeforeEach;
import org.junit.jupiter.api.Test;

/**
 * The bad-frame corpus against node b, each from a raw socket, while a legitimate node c stays
 * connected to b: each closes only the offending connection, with a logged, counted reason.
 */
class NetworkBadInputIT {

    private static final Profile ECHO = Profile.of("echo");
    private static final Profile SINK = Profile.of("sink");

    private TestNode b;
    private TestNode c;
    private final LinkedBlockingQueue<Message> sunk = new LinkedBlockingQueue<>();

    @BeforeEach
    void connectLegitimateNodes() throws Exception {
        b = TestNode.start("b", TestNode.config().handshakeTimeout(Duration.ofMillis(500)));
        b.node.add(ECHO, () -> (message, context) -> context.reply(message, message.contents()));
        b.node.add(SINK, () -> (message, context) -> sunk.add(message));
        c = TestNode.start("c", TestNode.config().peer(b.address()));
        assertTrue(c.net.awaitResolvable(ECHO, Duration.ofSeconds(30)));
        assertTrue(c.net.awaitConnected("b", Duration.ofSeconds(30)), "both lanes are up");
    }

    @AfterEach
    void close() {
        c.close();
        b.close();
    }

    /** The attack closed only its own connection: c is still connected through its first one. */
    private void assertOnlyTheOffenderWasClosed(CloseReason reason) {
        Await.until("b counts the " + reason + " close", () -> b.net.stats().closes(reason) == 1);
        assertEquals(1, b.net.stats().badInputCloses(), b.net.stats().toString());
        assertEquals(new Text("after the attack"), c.node.requestBlocking(ECHO, new Text("after the attack")).contents());
        assertEquals(TestNode.LANES, c.net.stats().connectionsOpened(), "c never had to reconnect");
        assertEquals(0, c.net.stats().closes().size(), c.net.stats().toString());
    }

    private static RawPeer.Received byeOf(List<RawPeer.Received> frames) {
        return frames.stream().filter(frame -> frame.type() == RawPeer.BYE).findFirst()
                .orElseThrow(() -> new AssertionError("no BYE before the close"));
    }

    @Test
    void shouldCloseAConnectionThatSpeaksHttp() throws Exception {
        try (var attacker = new RawPeer(b.address())) {
            attacker.raw("GET / HTTP/1.1\r\nHost: b\r\n\r\n".getBytes(StandardCharsets.US_ASCII));
            List<RawPeer.Received> frames = attacker.readUntilClosed();
            assertEquals(RawPeer.HELLO, frames.getFirst().type(), "the node introduces itself first");
            assertEquals(CloseReason.BAD_HANDSHAKE.code(), byeOf(frames).byeCode());
            assertTrue(byeOf(frames).byeText().contains("not an Etherware peer"), byeOf(frames).byeText());
        }
        assertOnlyTheOffenderWasClosed(CloseReason.BAD_HANDSHAKE);
    }

    @Test
    void shouldCloseAConnectionThatSendsGarbageBytes() throws Exception {
        byte[] garbage = new byte[256];
        new Random(42).nextBytes(garbage);
        try (var attacker = new RawPeer(b.address())) {
            attacker.raw(garbage);
            assertEquals(CloseReason.BAD_HANDSHAKE.code(), byeOf(attacker.readUntilClosed()).byeCode());
        }
        assertOnlyTheOffenderWasClosed(CloseReason.BAD_HANDSHAKE);
    }

    @Test
    void shouldCloseAConnectionWithAWrongMagic() throws Exception {
        try (var attacker = new RawPeer(b.address())) {
            attacker.hello(0x12345678, RawPeer.VERSION, "mallory");
            assertEquals(CloseReason.BAD_HANDSHAKE.code(), byeOf(attacker.readUntilClosed()).byeCode());
        }
        assertOnlyTheOffenderWasClosed(CloseReason.BAD_HANDSHAKE);
    }

    @Test
    void shouldCloseAConnectionOfAnotherProtocolVersion() throws Exception {
        try (var attacker = new RawPeer(b.address())) {
            attacker.hello(RawPeer.MAGIC, RawPeer.VERSION + 1, "mallory");
            RawPeer.Received bye = byeOf(attacker.readUntilClosed());
            assertEquals(CloseReason.PROTOCOL_VERSION.code(), bye.byeCode());
            assertTrue(bye.byeText().contains("version 3"), bye.byeText());
        }
        assertOnlyTheOffenderWasClosed(CloseReason.PROTOCOL_VERSION);
    }

    @Test
    void shouldCloseAConnectionThatClaimsTheNodesOwnId() throws Exception {
        try (var attacker = new RawPeer(b.address())) {
            attacker.hello(RawPeer.MAGIC, RawPeer.VERSION, "b");
            assertEquals(CloseReason.BAD_HANDSHAKE.code(), byeOf(attacker.readUntilClosed()).byeCode());
        }
        assertOnlyTheOffenderWasClosed(CloseReason.BAD_HANDSHAKE);
    }

    @Test
    void shouldCloseAConnectionThatNeverCompletesTheHandshake() throws Exception {
        try (var attacker = new RawPeer(b.address())) {
            assertEquals(CloseReason.HANDSHAKE_TIMEOUT.code(), byeOf(attacker.readUntilClosed()).byeCode());
        }
        assertOnlyTheOffenderWasClosed(CloseReason.HANDSHAKE_TIMEOUT);
    }

    /**
     * A peer that says BYE where its RESUME was due (it is shutting down, or its own side of the
     * handshake failed, as when a connection is cut while both ends handshake) has left; it broke
     * no rule, so the close is not counted as bad input.
     */
    @Test
    void shouldTakeAByeInsideTheHandshakeAsThePeerLeavingNotAsBadInput() throws Exception {
        try (var peer = new RawPeer(b.address())) {
            peer.hello(RawPeer.MAGIC, RawPeer.VERSION, "mallory");
            peer.expect(RawPeer.HELLO);
            peer.bye(CloseReason.SHUTDOWN.code(), "going away");
            List<RawPeer.Received> frames = peer.readUntilClosed();
            assertTrue(frames.stream().noneMatch(frame -> frame.type() == RawPeer.BYE),
                    "no BYE back to a peer that left: " + frames);
        }
        Await.until("b counts the peer's close", () -> b.net.stats().closes(CloseReason.PEER_CLOSED) == 1);
        assertEquals(0, b.net.stats().badInputCloses(), b.net.stats().toString());
        assertEquals(new Text("after the goodbye"), c.node.requestBlocking(ECHO, new Text("after the goodbye")).contents());
        assertEquals(0, c.net.stats().closes().size(), c.net.stats().toString());
    }

    @Test
    void shouldCloseAConnectionThatSendsAnOversizeFrame() throws Exception {
        try (var attacker = new RawPeer(b.address())) {
            attacker.handshake("mallory");
            attacker.raw(new byte[] {0x00, 0x20, 0x00, 0x00, RawPeer.DATA}); // 2 MiB announced
            RawPeer.Received bye = byeOf(attacker.readUntilClosed());
            assertEquals(CloseReason.OVERSIZE_FRAME.code(), bye.byeCode());
            assertTrue(bye.byeText().contains("2097152"), bye.byeText());
        }
        assertOnlyTheOffenderWasClosed(CloseReason.OVERSIZE_FRAME);
    }

    @Test
    void shouldRejectAMessageOfMalformedXmlAndCloseItsConnection() throws Exception {
        try (var attacker = new RawPeer(b.address())) {
            attacker.handshake("mallory");
            attacker.data(0, "<message version=\"1\"><profile>sink</profile><oops");
            List<RawPeer.Received> frames = attacker.readUntilClosed();
            assertTrue(frames.stream().anyMatch(frame -> frame.type() == RawPeer.REJECT), "the message is refused");
            assertEquals(CloseReason.MALFORMED_MESSAGE.code(), byeOf(frames).byeCode());
        }
        assertOnlyTheOffenderWasClosed(CloseReason.MALFORMED_MESSAGE);
        assertTrue(sunk.isEmpty());
    }

    @Test
    void shouldCloseAConnectionThatSendsAnUnknownFrameType() throws Exception {
        try (var attacker = new RawPeer(b.address())) {
            attacker.handshake("mallory");
            attacker.frame(99, new byte[] {1, 2, 3});
            assertEquals(CloseReason.MALFORMED_FRAME.code(), byeOf(attacker.readUntilClosed()).byeCode());
        }
        assertOnlyTheOffenderWasClosed(CloseReason.MALFORMED_FRAME);
    }

    @Test
    void shouldCloseAConnectionThatAnnouncesAMalformedProfile() throws Exception {
        try (var attacker = new RawPeer(b.address())) {
            attacker.handshake("mallory");
            attacker.frame(RawPeer.ANNOUNCE, RawPeer.body(out -> {
                out.writeLong(1);
                out.writeInt(1);
                RawPeer.string(out, "not a profile!");
            }));
            assertEquals(CloseReason.MALFORMED_FRAME.code(), byeOf(attacker.readUntilClosed()).byeCode());
        }
        assertOnlyTheOffenderWasClosed(CloseReason.MALFORMED_FRAME);
    }

    @Test
    void shouldCloseAConnectionThatSkipsMessageNumbers() throws Exception {
        try (var attacker = new RawPeer(b.address())) {
            attacker.handshake("mallory");
            attacker.data(5, new MessageCodec(Num.register(new io.etherware.core.message.ContentsTypes())).encodeToString(message("skipped ahead")));
            assertEquals(CloseReason.SEQUENCE_ERROR.code(), byeOf(attacker.readUntilClosed()).byeCode());
        }
        assertOnlyTheOffenderWasClosed(CloseReason.SEQUENCE_ERROR);
        assertTrue(sunk.isEmpty());
    }

    @Test
    void shouldRefuseAPeerClaimingMessagesNeverSentAndStartTheStreamAfresh() throws Exception {
        long firstStreamId;
        try (var attacker = new RawPeer(b.address())) {
            firstStreamId = attacker.handshakeClaiming("mallory", 0, 5);
            RawPeer.Received bye = byeOf(attacker.readUntilClosed());
            assertEquals(CloseReason.SEQUENCE_ERROR.code(), bye.byeCode());
            assertTrue(bye.byeText().contains("claims 5 messages"), bye.byeText());
        }
        assertOnlyTheOffenderWasClosed(CloseReason.SEQUENCE_ERROR);
        try (var again = new RawPeer(b.address())) {
            long secondStreamId = again.handshakeClaiming("mallory", firstStreamId, 5);
            assertTrue(secondStreamId != firstStreamId, "b starts its stream to mallory under a new id");
            assertEquals(RawPeer.ANNOUNCE, again.read().type(), "the stale claim no longer matters: connected");
        }
    }

    @Test
    void shouldDeliverAMessageFromAPeerThatFollowsTheDocument() throws Exception {
        try (var peer = new RawPeer(b.address())) {
            peer.handshake("mallory");
            peer.data(0, new MessageCodec(Num.register(new io.etherware.core.message.ContentsTypes())).encodeToString(message("by the book")));
            Message arrived = sunk.poll(30, TimeUnit.SECONDS);
            assertEquals(new Text("by the book"), arrived.contents());
            assertEquals(new MessageId("mallory", 1), arrived.messageId());
        }
        // The raw peer closes without reading what b sent it (acknowledgements, announcements), so
        // its kernel may reset the connection rather than end it: b sees either, never bad input.
        Await.until("b sees the peer leave", () -> b.net.stats().closes(CloseReason.PEER_CLOSED)
                + b.net.stats().closes(CloseReason.IO_ERROR) == 1);
        assertEquals(0, b.net.stats().badInputCloses(), () -> b.net.stats().toString());
    }

    private static Message message(String text) {
        return new Message(SINK, null, System.currentTimeMillis() * 1_000_000L, QoS.NONE, new Text(text),
                new MessageId("mallory", 1), null);
    }
}
