package io.etherware.services.network;

import static org.junit.jupiter.api.Assertions.assertEquals;
import static org.junit.jupiter.api.Assertions.assertThrows;
import static org.junit.jupiter.api.Assertions.assertTrue;

import io.etherware.core.kernel.EtherwareNode;
import io.etherware.testkit.Await;
import java.io.UncheckedIOException;
import java.net.InetSocketAddress;
import java.time.Duration;
import org.junit.jupiter.api.Test;

/**
 * The configuration at start, on real loopback sockets: a taken port fails naming it, and every
 * socket is made through the configured factory. Build-time checks are {@link NetworkConfigTest}'s.
 */
class NetworkConfigIT {

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
