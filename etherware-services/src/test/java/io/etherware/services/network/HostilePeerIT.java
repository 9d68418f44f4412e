package io.etherware.services.network;

import static io.etherware.services.network.HostileKit.ECHO;
import static io.etherware.services.network.HostileKit.LEGIT_TIMEOUT_MS;
import static io.etherware.services.network.HostileKit.nodeProfile;
import static org.junit.jupiter.api.Assertions.assertEquals;
import static org.junit.jupiter.api.Assertions.assertFalse;
import static org.junit.jupiter.api.Assertions.assertInstanceOf;
import static org.junit.jupiter.api.Assertions.assertTrue;

import io.etherware.core.component.RequestFailedException;
import io.etherware.core.kernel.Undeliverable;
import io.etherware.core.message.Message;
import io.etherware.core.message.MessageId;
import io.etherware.core.message.Profile;
import io.etherware.core.message.Text;
import io.etherware.testkit.Await;
import java.io.IOException;
import java.io.InputStream;
import java.net.InetSocketAddress;
import java.net.Socket;
import java.nio.file.Files;
import java.security.KeyStore;
import java.time.Duration;
import java.util.List;
import java.util.concurrent.CompletableFuture;
import java.util.concurrent.ExecutionException;
import java.util.concurrent.LinkedBlockingQueue;
import java.util.concurrent.TimeUnit;
import javax.net.ssl.SSLContext;
import javax.net.ssl.TrustManagerFactory;
import org.junit.jupiter.api.AfterEach;
import org.junit.jupiter.api.BeforeAll;
import org.junit.jupiter.api.BeforeEach;
import org.junit.jupiter.api.Test;

/**
 * Hostile peers over mutual TLS: node {@code legit} requests the {@code echo} component of node
 * {@code target} every 10 ms while {@code mallory}, a node of the same deployment with a valid
 * certificate of its own (or no certificate at all), written as a {@link RawPeer}, tries to pass
 * for another node, to send under other nodes' ids, to draw routes to itself and to answer the
 * legitimate peer's requests. Each attack is refused and counted; the legitimate peer loses
 * nothing.
 */
class HostilePeerIT {

    private static final Profile SINK = Profile.of("sink");
    private static final Profile SILENT = Profile.of("silent");

    private TestNode target;
    private TestNode legit;
    private LegitLoad load;
    /** The legitimate connection as the target sees it (the legitimate peer's address and port). */
    private String legitConnection;
    private final LinkedBlockingQueue<Message> sunk = new LinkedBlockingQueue<>();

    private static NetworkConfig.Builder tls(String nodeId) {
        return TestNode.config().connectionFactory(TestPki.deployment().factory(nodeId));
    }

    @BeforeEach
    void startTheLegitimateTraffic() throws Exception {
        // A grace far above what the tests wait: routes removed within it were removed at once.
        target = TestNode.start("target", tls("target").peerDownGrace(Duration.ofSeconds(60)));
        target.node.add(ECHO, HostileKit.echo());
        target.node.add(SINK, () -> (message, context) -> sunk.add(message));
        target.node.add(SILENT, () -> (message, context) -> { });
        legit = TestNode.start("legit", tls("legit").peer(target.address()));
        assertTrue(legit.net.awaitResolvable(ECHO, Duration.ofSeconds(30)));
        assertTrue(target.net.awaitConnected("legit", Duration.ofSeconds(30)), "both of legit's lanes are up");
        load = LegitLoad.start(legit.node, ECHO, LEGIT_TIMEOUT_MS);
        Await.until("the legitimate requests flow", () -> load.answered() >= 20);
        legitConnection = target.net.peer("legit").orElseThrow().remote().orElseThrow();
    }

    /** Makes the deployment's key stores side by side: keytool is slow to start. */
    @BeforeAll
    static void makeCertificates() throws Exception {
        var pki = TestPki.deployment();
        var made = new java.util.ArrayList<CompletableFuture<?>>();
        for (String nodeId : List.of("target", "legit", "mallory")) {
            made.add(CompletableFuture.runAsync(() -> pki.keyStore(nodeId)));
        }
        CompletableFuture.allOf(made.toArray(CompletableFuture[]::new)).get();
    }

    @AfterEach
    void stop() {
        load.close();
        legit.close();
        target.close();
    }

    /** The legitimate peer lost nothing and never had to reconnect. */
    private void assertTheLegitPeerLostNothing() throws InterruptedException {
        Thread.sleep(200);
        load.stop();
        assertEquals(0, load.failures().size(), load.toString());
        assertEquals(load.sent(), load.answered(), load.toString());
        assertEquals(legitConnection, target.net.peer("legit").orElseThrow().remote().orElse("none"),
                "the legitimate connection is the one from the start: " + target.net.stats());
        assertEquals(0, legit.net.stats().badInputCloses(), legit.net.stats().toString());
    }

    /** A raw peer over a TLS connection authenticated with {@code nodeId}'s certificate. */
    private static RawPeer mallory(String certificateOf, InetSocketAddress node) throws IOException {
        ConnectionFactory factory = TestPki.deployment().factory(certificateOf);
        Socket socket = factory.connect(node, 5_000);
        factory.authenticate(socket);
        return new RawPeer(socket);
    }

    /** Completes the handshake as {@code nodeId} on a stream of the peer's choosing. */
    private static void connectAs(RawPeer peer, String nodeId, long streamId) throws IOException {
        RawPeer.Resume node = peer.introduce(nodeId);
        peer.resume(streamId, node.streamId(), 0);
        assertEquals(RawPeer.ANNOUNCE, peer.read().type(), nodeId + " is connected");
    }

    @Test
    void shouldKeepAnImpostorOfTheLegitPeerOutAtTheHandshakeOverTls() throws Exception {
        // Another node's valid certificate, HELLO naming the legitimate peer.
        try (var impostor = mallory("mallory", target.address())) {
            impostor.hello(RawPeer.MAGIC, RawPeer.VERSION, "legit");
            assertRefused(impostor);
        }
        // No certificate: a TLS client that trusts the deployment's CA but has no key.
        try (var impostor = new RawPeer(withoutCertificate(target.address()))) {
            impostor.hello(RawPeer.MAGIC, RawPeer.VERSION, "legit");
            assertRefused(impostor);
        } catch (IOException refused) {
            // The TLS 1.3 server refuses the missing certificate after the client's side completed.
        }
        // Plain TCP speaking the protocol to the TLS port: what comes back is no HELLO frame.
        try (var impostor = new RawPeer(target.address())) {
            impostor.hello(RawPeer.MAGIC, RawPeer.VERSION, "legit");
            byte[] answer = impostor.readRawUntilClosed(64);
            assertFalse(answer.length >= 5 && answer[0] == 0 && answer[4] == RawPeer.HELLO,
                    "the node answered plain TCP with a HELLO");
        }
        Await.until("the target refused all three", () ->
                target.net.stats().closes(CloseReason.AUTHENTICATION_FAILED) == 3);
        assertEquals(TestNode.LANES, target.net.stats().connectionsOpened(), "only the legitimate peer's lanes: "
                + target.net.stats());
        assertEquals(3, target.net.stats().handshakesFailed(), target.net.stats().toString());
        assertTheLegitPeerLostNothing();
    }

    /** The node reads no HELLO back, or a BYE, before the connection ends. */
    private static void assertRefused(RawPeer impostor) throws IOException {
        try {
            List<RawPeer.Received> frames = impostor.readUntilClosed();
            assertTrue(frames.stream().noneMatch(frame -> frame.type() == RawPeer.RESUME),
                    "the impostor never gets to RESUME: " + frames.size() + " frames");
        } catch (javax.net.ssl.SSLException refused) {
            // The TLS layer said no: refused as well.
        }
    }

    private static Socket withoutCertificate(InetSocketAddress node) throws Exception {
        var trust = KeyStore.getInstance("PKCS12");
        try (InputStream in = Files.newInputStream(TestPki.deployment().trustStore())) {
            trust.load(in, TestPki.PASSWORD);
        }
        var trustManagers = TrustManagerFactory.getInstance(TrustManagerFactory.getDefaultAlgorithm());
        trustManagers.init(trust);
        var context = SSLContext.getInstance("TLSv1.3");
        context.init(null, trustManagers.getTrustManagers(), null);
        var socket = (javax.net.ssl.SSLSocket) context.getSocketFactory().createSocket(node.getAddress(),
                node.getPort());
        socket.startHandshake();
        return socket;
    }

    @Test
    void shouldRefuseMessagesSentDirectlyUnderTheTargetsOrTheLegitPeersId() throws Exception {
        long stream = 100;
        try (var attacker = mallory("mallory", target.address())) {
            connectAs(attacker, "mallory", stream);
            // Control: under its own id the attacker's message is delivered.
            attacker.data(0, 0, 0, HostileKit.xml(SINK, null, new Text("own"), new MessageId("mallory", 1), null));
            assertEquals(new Text("own"), sunk.poll(30, TimeUnit.SECONDS).contents());
        }
        for (String spoofed : List.of("target", "legit")) {
            try (var attacker = mallory("mallory", target.address())) {
                connectAs(attacker, "mallory", ++stream);
                attacker.data(0, 0, 0, HostileKit.xml(SINK, null, new Text("spoofed " + spoofed),
                        new MessageId(spoofed, 7), null));
                List<RawPeer.Received> frames = attacker.readUntilClosed();
                assertTrue(frames.stream().anyMatch(frame -> frame.type() == RawPeer.REJECT), "refused by REJECT");
                RawPeer.Received bye = frames.stream().filter(frame -> frame.type() == RawPeer.BYE).findFirst()
                        .orElseThrow();
                assertEquals(CloseReason.ORIGIN_MISMATCH.code(), bye.byeCode(), bye.byeText());
            }
        }
        Await.until("both spoofs counted", () -> target.net.stats().closes(CloseReason.ORIGIN_MISMATCH) == 2);
        assertEquals(null, sunk.poll(200, TimeUnit.MILLISECONDS), "no spoofed message reached the component");
        assertTheLegitPeerLostNothing();
    }

    @Test
    void shouldRefuseAnAnnouncementOfTheLegitPeersNodeProfile() throws Exception {
        try (var attacker = mallory("mallory", target.address())) {
            connectAs(attacker, "mallory", 1);
            attacker.announce(1, nodeProfile("mallory").toString(), nodeProfile("legit").toString(),
                    nodeProfile("target").toString());
            Await.until("the target refused two node profiles", () -> target.net.stats().announcementsRefused() == 2);
            Await.until("the target routes mallory's own", () -> target.net.peer("mallory")
                    .map(status -> status.profiles().contains(nodeProfile("mallory"))).orElse(false));
            Thread.sleep(300); // replies to legit keep flowing while mallory is connected
            assertTrue(target.net.peer("legit").orElseThrow().profiles().contains(nodeProfile("legit")));
            assertFalse(target.net.peer("mallory").orElseThrow().profiles().contains(nodeProfile("legit")));
        }
        assertTheLegitPeerLostNothing();
    }

    @Test
    void shouldNotLetAPeerAnnouncingTheEchoProfileDrawTheLegitPeersRequests() throws Exception {
        int drawn = 0;
        try (var attacker = mallory("mallory", legit.address())) { // the legitimate peer's own listener
            connectAs(attacker, "mallory", 1);
            attacker.announce(1, nodeProfile("mallory").toString(), ECHO.toString());
            Await.until("legit heard the claim", () -> legit.net.peer("mallory").isPresent());
            long sentBefore = load.sent();
            attacker.soTimeoutMs(100);
            while (load.sent() < sentBefore + 50) { // 50 legitimate requests while the claim stands
                try {
                    if (attacker.read().type() == RawPeer.DATA) {
                        drawn++;
                    }
                } catch (java.net.SocketTimeoutException idle) {
                    attacker.heartbeat();
                }
            }
            assertTrue(legit.net.peer("target").orElseThrow().profiles().contains(ECHO), "echo stays with target");
            assertFalse(legit.net.peer("mallory").orElseThrow().profiles().contains(ECHO));
        }
        assertEquals(0, drawn, "no request went to the attacker");
        assertTheLegitPeerLostNothing();
    }

    @Test
    void shouldUnrouteAPeerThatSaysByeShutdownAtOnce() throws Exception {
        Profile service = Profile.of("mallory-service");
        try (var attacker = mallory("mallory", target.address())) {
            connectAs(attacker, "mallory", 1);
            attacker.announce(1, nodeProfile("mallory").toString(), service.toString());
            assertTrue(target.net.awaitResolvable(service, Duration.ofSeconds(30)));
            attacker.bye(CloseReason.SHUTDOWN.code(), "going away");
            attacker.readUntilClosed();
        }
        // The grace is 60 s: gone within 10 s means gone at the BYE, not at the grace's end.
        Await.until("the target unrouted mallory's profiles", 10_000, () -> !resolvable(target, service));
        assertTrue(target.net.peer("mallory").map(status -> status.profiles().isEmpty()).orElse(true));
        assertTheLegitPeerLostNothing();
    }

    private static boolean resolvable(TestNode node, Profile profile) {
        try {
            return node.net.awaitResolvable(profile, Duration.ZERO);
        } catch (InterruptedException e) {
            Thread.currentThread().interrupt();
            return false;
        }
    }

    /**
     * A peer with a valid certificate of its own answers a request the legitimate peer made to
     * another node: a message to the legitimate node's profile whose correlation id is the
     * request's, under the attacker's own id (so it passes the origin check), relayed by the
     * target. Message ids are a node's id and a counter, easily guessed; the test hands them over.
     */
    @Test
    void shouldNotLetAThirdNodeAnswerOrFailTheLegitPeersRequests() throws Exception {
        var toBeForged = outsideRequest(legit, SILENT);
        var toBeFailed = outsideRequest(legit, SILENT);
        try (var attacker = mallory("mallory", target.address())) {
            connectAs(attacker, "mallory", 1);
            attacker.data(0, 0, 0, HostileKit.xml(nodeProfile("legit"), nodeProfile("mallory"), new Text("forged"),
                    new MessageId("mallory", 1), toBeForged.id()));
            attacker.data(1, 0, 0, HostileKit.xml(nodeProfile("legit"), nodeProfile("mallory"),
                    new Undeliverable(SILENT.toString(), toBeFailed.id().toString(), "forged"),
                    new MessageId("mallory", 2), toBeFailed.id()));
            assertTimesOut(toBeForged.reply());
            assertTimesOut(toBeFailed.reply());
        }
        assertTheLegitPeerLostNothing();
    }

    private record Pending(MessageId id, CompletableFuture<Message> reply) {
    }

    private static Pending outsideRequest(TestNode from, Profile to) {
        var request = new Message(to, from.node.profile(), from.node.clock().epochNanos(), HostileKit.HIGH,
                new Text("?"), from.node.newMessageId(), null);
        return new Pending(request.messageId(), from.node.request(request, TimeUnit.SECONDS.toNanos(2)));
    }

    private static void assertTimesOut(CompletableFuture<Message> reply) throws InterruptedException {
        try {
            Message answer = reply.get(30, TimeUnit.SECONDS);
            throw new AssertionError("the silent component's request was answered by " + answer.origin() + ": "
                    + answer.contents());
        } catch (ExecutionException e) {
            var failure = assertInstanceOf(RequestFailedException.class, e.getCause());
            assertEquals(RequestFailedException.Reason.TIMEOUT, failure.reason(), failure.getMessage());
        } catch (java.util.concurrent.TimeoutException e) {
            throw new AssertionError("the request neither timed out nor was answered", e);
        }
    }
}
