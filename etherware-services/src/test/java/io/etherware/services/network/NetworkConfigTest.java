package io.etherware.services.network;

import static org.junit.jupiter.api.Assertions.assertEquals;
import static org.junit.jupiter.api.Assertions.assertSame;
import static org.junit.jupiter.api.Assertions.assertThrows;
import static org.junit.jupiter.api.Assertions.assertTrue;

import io.etherware.core.kernel.EtherwareNode;
import io.etherware.testkit.Await;
import java.io.UncheckedIOException;
import java.net.InetSocketAddress;
import java.time.Duration;
import org.junit.jupiter.api.Test;

/** Misconfiguration fails at build time naming the field; a taken port fails at start naming it. */
class NetworkConfigTest {

    private static String errorOf(NetworkConfig.Builder builder) {
        return assertThrows(IllegalArgumentException.class, builder::build).getMessage();
    }

    @Test
    void shouldNameTheFieldAndValueOfABadSetting() {
        assertTrue(errorOf(NetworkConfig.builder().maxFrameBytes(100)).startsWith("maxFrameBytes=100"));
        assertTrue(errorOf(NetworkConfig.builder().queueCapacity(0)).startsWith("queueCapacity=0"));
        assertTrue(errorOf(NetworkConfig.builder().windowMessages(1)).startsWith("windowMessages=1"));
        String heartbeat = errorOf(NetworkConfig.builder().heartbeatInterval(Duration.ofSeconds(2))
                .heartbeatTimeout(Duration.ofSeconds(3)));
        assertTrue(heartbeat.startsWith("heartbeatTimeoutNs=3000000000") && heartbeat.contains("twice"), heartbeat);
        assertTrue(errorOf(NetworkConfig.builder().reconnectBackoff(Duration.ofSeconds(1), Duration.ofMillis(10), 0.2))
                .startsWith("reconnectMaxBackoffNs=10000000"));
        assertTrue(errorOf(NetworkConfig.builder().reconnectBackoff(Duration.ofMillis(10), Duration.ofSeconds(1), 1.0))
                .startsWith("reconnectJitter=1.0"));
        assertTrue(errorOf(NetworkConfig.builder().timeProbes(Duration.ofSeconds(1), 100)).startsWith("timeProbeBurst=100"));
        assertTrue(errorOf(NetworkConfig.builder().maxHops(-1)).startsWith("maxHops=-1"));
    }

    @Test
    void shouldFitTheDefaultCodecToTheFrameLimitOverTheNodesContentsTypes() {
        NetworkConfig config = NetworkConfig.builder().maxFrameBytes(64 * 1024).build();
        var node = EtherwareNode.builder().nodeId("fit").build();
        var codec = config.codecFor(node);
        assertTrue(codec.maxDocumentBytes() < config.maxFrameBytes(), () -> "document limit " + codec.maxDocumentBytes());
        assertSame(node.contentsTypes(), codec.contentsTypes());
        assertTrue(codec.contentsTypes().names().contains("undeliverable"), () -> codec.contentsTypes().names().toString());
        assertEquals(NetworkConfig.DEFAULT_MAX_FRAME_BYTES, NetworkConfig.builder().build().maxFrameBytes());
    }

    @Test
    void shouldSayWhichAddressCannotBeBoundAndCloseWithItsNode() throws Exception {
        try (var node = EtherwareNode.builder().nodeId("a").build().start();
             var first = NetworkMessenger.start(node, NetworkConfig.builder().build())) {
            InetSocketAddress taken = first.localAddress();
            try (var other = EtherwareNode.builder().nodeId("b").build().start()) {
                var error = assertThrows(UncheckedIOException.class,
                        () -> NetworkMessenger.start(other, NetworkConfig.builder().listen(taken).build()));
                assertTrue(error.getMessage().contains(String.valueOf(taken.getPort())), error.getMessage());
            }
            try (var b = EtherwareNode.builder().nodeId("b").build().start()) {
                var messenger = NetworkMessenger.start(b, NetworkConfig.builder().peer(taken).build());
                assertTrue(first.awaitConnected("b", Duration.ofSeconds(30)));
                b.close();
                Await.until("closing node b closed its messenger, which said BYE on every lane",
                        () -> first.stats().closes(CloseReason.PEER_CLOSED) >= TestNode.LANES);
                assertEquals(TestNode.LANES, first.stats().closes(CloseReason.PEER_CLOSED), first.stats().toString());
                assertEquals(1, first.stats().closes().size(), "no other close: " + first.stats());
                assertTrue(!first.peer("b").orElseThrow().connected());
                messenger.close(); // idempotent
            }
        }
    }

    @Test
    void shouldMakeEverySocketThroughTheConnectionFactory() throws Exception {
        var listened = new java.util.concurrent.atomic.AtomicInteger();
        var dialed = new java.util.concurrent.atomic.AtomicInteger();
        ConnectionFactory counting = new ConnectionFactory() {
            @Override
            public java.net.ServerSocket listen(InetSocketAddress address) throws java.io.IOException {
                listened.incrementAndGet();
                return ConnectionFactory.plain().listen(address);
            }

            @Override
            public java.net.Socket connect(InetSocketAddress address, int timeoutMs) throws java.io.IOException {
                dialed.incrementAndGet();
                return ConnectionFactory.plain().connect(address, timeoutMs);
            }
        };
        try (var b = TestNode.start("b", TestNode.config().connectionFactory(counting));
             var a = TestNode.start("a", TestNode.config().connectionFactory(counting).peer(b.address()))) {
            assertTrue(a.net.awaitConnected("b", Duration.ofSeconds(30)));
            assertEquals(2, listened.get());
            assertEquals(TestNode.LANES, dialed.get(), "one connection per lane");
        }
    }
}
