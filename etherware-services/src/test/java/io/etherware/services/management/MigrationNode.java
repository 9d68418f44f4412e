package io.etherware.services.management;

import example.counter.ReportingCounter;
import io.etherware.core.kernel.EtherwareNode;
import io.etherware.core.message.ContentsTypes;
import io.etherware.core.scheduler.Scheduler;
import io.etherware.services.network.NetworkConfig;
import io.etherware.services.network.NetworkMessenger;
import java.net.InetSocketAddress;
import java.time.Duration;
import java.util.Set;
import java.util.function.Supplier;

/**
 * A node on loopback with a NetworkMessenger and a management service that can migrate, for tests.
 * What the messenger delivers carries the {@link io.etherware.core.message.Origin} of its plain-TCP
 * connection, so the access lists are exercised as between real nodes.
 */
final class MigrationNode implements AutoCloseable {

    final EtherwareNode node;
    final NetworkMessenger net;
    final ManagementService management;

    private MigrationNode(EtherwareNode node, NetworkMessenger net, ManagementService management) {
        this.node = node;
        this.net = net;
        this.management = management;
    }

    /**
     * Migrations in both directions between the test's nodes: any node may migrate anything here,
     * over the plain-TCP loopback links of the tests.
     */
    static ManagementConfig.Builder config() {
        return ManagementConfig.builder().allowRemote(AccessRule.ANY_NODE, Set.of(AccessRule.Operation.MIGRATE),
                AccessRule.ANY_PROFILE).allowUnauthenticatedLinks(true);
    }

    static MigrationNode start(String nodeId, ManagementConfig config, InetSocketAddress... peers) {
        return start(nodeId, null, config, peers);
    }

    /** A node on loopback (any port) dialing {@code peers}; {@code scheduler} null for the default. */
    static MigrationNode start(String nodeId, Supplier<? extends Scheduler> scheduler, ManagementConfig config,
                               InetSocketAddress... peers) {
        var types = new ContentsTypes();
        ReportingCounter.register(types);
        var builder = EtherwareNode.builder().nodeId(nodeId).contentsTypes(types)
                .defaultRequestTimeout(Duration.ofSeconds(30));
        if (scheduler != null) {
            builder.scheduler(scheduler);
        }
        EtherwareNode node = builder.build().start();
        var network = NetworkConfig.builder().listen(new InetSocketAddress("127.0.0.1", 0))
                .reconnectBackoff(Duration.ofMillis(20), Duration.ofMillis(200), 0.2)
                .timeProbes(Duration.ofMillis(100), 4);
        for (InetSocketAddress peer : peers) {
            network.peer(peer);
        }
        NetworkMessenger net;
        try {
            net = NetworkMessenger.start(node, network.build());
        } catch (RuntimeException e) {
            node.close();
            throw e;
        }
        return new MigrationNode(node, net, ManagementService.install(node, config, net));
    }

    InetSocketAddress address() {
        return net.localAddress();
    }

    /** Waits until the management service of {@code nodeId} is reachable from here. */
    void awaitManagementOf(String nodeId) throws InterruptedException {
        if (!net.awaitResolvable(Management.profileOf(nodeId), Duration.ofSeconds(30))) {
            throw new AssertionError("node '" + node.nodeId() + "' does not reach the management service of '"
                    + nodeId + "'");
        }
    }

    @Override
    public void close() {
        net.close();
        node.close();
    }
}
