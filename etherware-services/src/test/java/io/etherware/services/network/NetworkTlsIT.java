package io.etherware.services.network;

import static org.junit.jupiter.api.Assertions.assertEquals;
import static org.junit.jupiter.api.Assertions.assertFalse;
import static org.junit.jupiter.api.Assertions.assertThrows;
import static org.junit.jupiter.api.Assertions.assertTrue;

import io.etherware.core.message.Origin;
import io.etherware.core.message.Profile;
import io.etherware.core.message.Text;
import io.etherware.testkit.Await;
import java.io.IOException;
import java.io.UncheckedIOException;
import java.net.InetSocketAddress;
import java.net.Socket;
import java.time.Duration;
import java.util.Optional;
import org.junit.jupiter.api.BeforeAll;
import org.junit.jupiter.api.Test;

/** Mutual TLS between nodes: who a peer is comes from its certificate, and nothing else. */
class NetworkTlsIT {

    private static final Profile WHO = Profile.of("who-sent-this");
    private static TestPki deployment;
    private static TestPki rogue;

    @BeforeAll
    static void makeCertificates() {
        deployment = TestPki.deployment();
        rogue = TestPki.rogue();
    }

    private static NetworkConfig.Builder tls(String nodeId) {
        return TestNode.config().connectionFactory(deployment.factory(nodeId));
    }

    /** Answers with the origin the network layer gave the request. */
    private static void addWho(TestNode node) {
        node.node.add(WHO, () -> (message, context) -> {
            Origin origin = message.origin();
            context.reply(message, new Text(origin == null ? "local"
                    : origin.nodeId() + " via " + origin.viaNodeId() + (origin.authenticated() ? " authenticated" : "")));
        });
    }

    @Test
    void shouldCarryAuthenticatedOriginsBetweenNodesOverMutualTls() throws Exception {
        try (var b = TestNode.start("b", tls("b"));
             var a = TestNode.start("a", tls("a").peer(b.address()))) {
            addWho(b);
            assertTrue(a.net.awaitResolvable(WHO, Duration.ofSeconds(30)));
            assertEquals(new Text("a via a authenticated"), a.node.requestBlocking(WHO, new Text("?")).contents());
            assertEquals(new Text("local"), b.node.requestBlocking(WHO, new Text("?")).contents());
        }
    }

    @Test
    void shouldRefuseAPeerWhoseHelloNamesAnotherNodeThanItsCertificate() throws Exception {
        try (var b = TestNode.start("b", tls("b"));
             var a = TestNode.start("a", tls("a").peer(b.address()))) {
            addWho(b);
            assertTrue(a.net.awaitResolvable(WHO, Duration.ofSeconds(30)));
            assertTrue(b.net.awaitConnected("a", Duration.ofSeconds(30)), "both of a's lanes are up at b");
            // mallory holds a valid certificate of the deployment, for 'mallory', and says it is 'a'.
            ConnectionFactory mallorysKey = deployment.factory("mallory");
            try (var raw = new RawPeer(authenticatedSocket(mallorysKey, b.address()))) {
                raw.handshake("a");
                throw new AssertionError("the handshake as 'a' with mallory's certificate went through");
            } catch (IOException | AssertionError expected) {
                if (expected instanceof AssertionError error && error.getMessage().contains("went through")) {
                    throw error;
                }
            }
            Await.until("b counted the failed authentication",
                    () -> b.net.stats().closes(CloseReason.AUTHENTICATION_FAILED) == 1);
            assertEquals(new Text("a via a authenticated"), a.node.requestBlocking(WHO, new Text("?")).contents(),
                    "the real a is still connected and served");
            assertEquals(TestNode.LANES, b.net.stats().connectionsOpened(), "the impostor never displaced a: "
                    + b.net.stats());
        }
    }

    @Test
    void shouldRefuseNodesOfAnotherCaAndPlainTcpPeers() throws Exception {
        try (var b = TestNode.start("b", tls("b"));
             var a = TestNode.start("a", tls("a").peer(b.address()))) {
            addWho(b);
            assertTrue(a.net.awaitResolvable(WHO, Duration.ofSeconds(30)));
            // A node of another deployment, named like a real one; and a plain-TCP node.
            try (var stranger = TestNode.start("c", TestNode.config()
                         .connectionFactory(TestPki.crossed(rogue, "c", deployment)).peer(b.address()));
                 var plain = TestNode.start("d", TestNode.config().peer(b.address()))) {
                Await.until("b refused both", () -> b.net.stats().handshakesFailed() >= 2);
                assertFalse(b.net.peer("c").map(PeerStatus::connected).orElse(false));
                assertFalse(b.net.peer("d").map(PeerStatus::connected).orElse(false));
                assertFalse(stranger.net.awaitResolvable(WHO, Duration.ofMillis(300)), "c never learns b's profiles");
            }
            assertEquals(new Text("a via a authenticated"), a.node.requestBlocking(WHO, new Text("?")).contents());
        }
    }

    @Test
    void shouldRefuseToStartWithTheCertificateOfAnotherNode() {
        var e = assertThrows(UncheckedIOException.class, () -> TestNode.start("a", tls("b")));
        assertTrue(e.getMessage().contains("names node 'b'"), e.getMessage());
    }

    @Test
    void shouldRefusePlainTcpBeyondLoopbackUnlessChosenInsecure() {
        var e = assertThrows(IllegalArgumentException.class,
                () -> NetworkConfig.builder().listen("0.0.0.0", 0).build());
        assertTrue(e.getMessage().startsWith("listenAddress=/0.0.0.0:0 is beyond loopback"), e.getMessage());
        var peer = assertThrows(IllegalArgumentException.class,
                () -> NetworkConfig.builder().peer(InetSocketAddress.createUnresolved("plant.example", 7400)).build());
        assertTrue(peer.getMessage().startsWith("peer=plant.example"), peer.getMessage());
        assertTrue(NetworkConfig.builder().listen("0.0.0.0", 0).insecure(true).build().isInsecureBeyondLoopback());
        assertFalse(NetworkConfig.builder().listen("0.0.0.0", 0).connectionFactory(deployment.factory("a")).build()
                .isInsecureBeyondLoopback(), "TLS may listen anywhere");
    }

    /** A TLS socket to {@code address}, handshaken, for a raw peer. */
    private static Socket authenticatedSocket(ConnectionFactory factory, InetSocketAddress address) throws IOException {
        Socket socket = factory.connect(address, 5_000);
        Optional<String> server = factory.authenticate(socket);
        assertEquals(Optional.of("b"), server, "the client authenticates the server too");
        return socket;
    }

}
