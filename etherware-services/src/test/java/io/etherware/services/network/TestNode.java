package io.etherware.services.network;

import io.etherware.core.kernel.EtherwareNode;
import io.etherware.core.time.NodeClock;
import java.net.InetSocketAddress;
import java.time.Duration;
import java.util.function.UnaryOperator;

/** A node with a messenger on loopback, configured for tests: quick redials, quick time probes. */
final class TestNode implements AutoCloseable {

    final EtherwareNode node;
    final NetworkMessenger net;

    private TestNode(EtherwareNode node, NetworkMessenger net) {
        this.node = node;
        this.net = net;
    }

    /** Test defaults: loopback, any port, redial after 20 ms up to 200 ms, time probes every 100 ms. */
    /** Connections per pair of nodes by default: one per lane. */
    static final int LANES = 2;

    static NetworkConfig.Builder config() {
        return NetworkConfig.builder()
                .listen(new InetSocketAddress("127.0.0.1", 0))
                .reconnectBackoff(Duration.ofMillis(20), Duration.ofMillis(200), 0.2)
                .timeProbes(Duration.ofMillis(100), 4);
    }

    static TestNode start(String nodeId, NetworkConfig.Builder config) {
        return start(nodeId, NodeClock.system(), config, builder -> builder);
    }

    static TestNode start(String nodeId, NodeClock clock, NetworkConfig.Builder config,
                          UnaryOperator<EtherwareNode.Builder> nodeSettings) {
        EtherwareNode node = nodeSettings.apply(EtherwareNode.builder().nodeId(nodeId).clock(clock)
                .contentsTypes(Num.register(new io.etherware.core.message.ContentsTypes()))
                .defaultRequestTimeout(Duration.ofSeconds(30))).build();
        node.start();
        try {
            return new TestNode(node, NetworkMessenger.start(node, config.build()));
        } catch (RuntimeException e) {
            node.close();
            throw e;
        }
    }

    InetSocketAddress address() {
        return net.localAddress();
    }

    @Override
    public void close() {
        net.close();
        node.close();
    }
}
