package io.etherware.deploy;

import io.etherware.core.kernel.EtherwareNode;
import io.etherware.core.scheduler.FifoScheduler;
import io.etherware.services.management.Management;
import io.etherware.services.network.ConnectionFactory;
import io.etherware.services.network.NetworkConfig;
import io.etherware.services.network.NetworkMessenger;
import io.etherware.services.network.PeerStatus;
import io.etherware.services.status.Status;
import java.net.InetAddress;
import java.net.InetSocketAddress;
import java.time.Duration;
import java.util.Objects;
import java.util.Optional;
import java.util.concurrent.TimeUnit;

/**
 * The control tool's side of a connection to a running node: a small node of its own (the
 * original FIFO scheduler, one ordinary thread; nothing real-time) that dials the node as a peer
 * does, and learns its id from the handshake. Opened by the tool's command for one request, then
 * closed. Used by one thread.
 */
final class ControlSession implements AutoCloseable {

    private static final long POLL_MS = 20;

    private final EtherwareNode node;
    private final NetworkMessenger network;
    private final String targetId;

    private ControlSession(EtherwareNode node, NetworkMessenger network, String targetId) {
        this.node = node;
        this.network = network;
        this.targetId = targetId;
    }

    /**
     * Connects to the node at {@code target}.
     *
     * @param id       this tool's node id (with TLS, the CN of its certificate; the target's access
     *                 list names it)
     * @param target   where the node listens
     * @param factory  plain TCP or TLS, as the node's network is
     * @param lanes    connections per pair of nodes, as the node's network has them
     * @param insecure whether plain TCP beyond loopback was chosen on purpose
     * @param timeout  how long to wait for the handshake
     * @return the open session
     * @throws ControlException naming the address and what to check, if no node answered in time
     */
    static ControlSession open(String id, InetSocketAddress target, ConnectionFactory factory, int lanes,
            boolean insecure, Duration timeout) throws ControlException {
        EtherwareNode node;
        try {
            node = EtherwareNode.builder().nodeId(id).scheduler(() -> new FifoScheduler("control")).build().start();
        } catch (RuntimeException e) {
            throw new ControlException("the tool's node '" + id + "' cannot start: " + e.getMessage(), e);
        }
        NetworkMessenger network = null;
        try {
            Status.registerContents(node.contentsTypes());
            Management.registerContents(node.contentsTypes());
            // Listens on loopback only, on a port nobody is told: the tool only dials.
            NetworkConfig config;
            try {
                config = NetworkConfig.builder().listen(new InetSocketAddress(InetAddress.getLoopbackAddress(), 0))
                        .peer(target).connectionFactory(factory).lanes(lanes).insecure(insecure)
                        .reconnectBackoff(Duration.ofMillis(50), Duration.ofMillis(200), 0.1).build();
            } catch (IllegalArgumentException e) {
                throw new ControlException(e.getMessage().contains("beyond loopback") ? HostPort.format(target)
                        + " is beyond loopback and plain TCP authenticates no one: give --key-store and --trust-store"
                        + " (TLS), or --insecure on a network you trust" : e.getMessage(), e);
            }
            network = NetworkMessenger.start(node, config);
            long deadline = System.nanoTime() + timeout.toNanos();
            Optional<String> connected = awaitPeer(network, target, deadline);
            if (connected.isEmpty()) {
                throw new ControlException("no node answered at " + HostPort.format(target) + " within " + timeout.toMillis()
                        + " ms: is it running, and does it listen there" + (factory.authenticatesPeers()
                        ? "? With TLS, check that both certificates chain to the trust store's CA"
                        : "? If its network uses TLS, give --trust-store and --key-store"));
            }
            // Its profiles arrive just after the handshake: wait for the status service's.
            long remainingNs = Math.max(deadline - System.nanoTime(), Duration.ofMillis(500).toNanos());
            if (!network.awaitResolvable(Status.profileOf(connected.get()), Duration.ofNanos(remainingNs))) {
                throw new ControlException("node " + connected.get() + " at " + HostPort.format(target) + " announced no"
                        + " status service (" + Status.profileOf(connected.get()) + "); a node the launcher started"
                        + " always has one");
            }
            return new ControlSession(node, network, connected.get());
        } catch (InterruptedException e) {
            Thread.currentThread().interrupt();
            closeBoth(network, node);
            throw new ControlException("interrupted while connecting", e);
        } catch (ControlException e) {
            closeBoth(network, node);
            throw e;
        } catch (RuntimeException e) {
            closeBoth(network, node);
            throw new ControlException("cannot connect to " + HostPort.format(target) + ": " + e.getMessage(), e);
        }
    }

    /** The id of the node that answered at {@code target}: not any peer that dialed the tool's own port. */
    private static Optional<String> awaitPeer(NetworkMessenger network, InetSocketAddress target, long deadline)
            throws ControlException {
        String dialed = target.getAddress().getHostAddress() + ":" + target.getPort();
        while (System.nanoTime() - deadline < 0) {
            for (PeerStatus peer : network.peers()) {
                if (peer.connected() && peer.remote().filter(remote -> remote.endsWith("/" + dialed)
                        || remote.equals(dialed)).isPresent()) {
                    return Optional.of(peer.nodeId());
                }
            }
            try {
                TimeUnit.MILLISECONDS.sleep(POLL_MS);
            } catch (InterruptedException e) {
                Thread.currentThread().interrupt();
                throw new ControlException("interrupted while connecting", e);
            }
        }
        return Optional.empty();
    }

    private static void closeBoth(NetworkMessenger network, EtherwareNode node) {
        try {
            if (network != null) {
                network.close();
            }
        } finally {
            node.close();
        }
    }

    /** {@return the tool's own node} */
    EtherwareNode node() {
        return node;
    }

    /**
     * Waits until the node's management service resolves.
     *
     * @param timeout how long at most
     * @throws ControlException if it does not: the node has no {@code <management>}
     */
    void requireManagement(Duration timeout) throws ControlException {
        try {
            if (!network.awaitResolvable(Management.profileOf(targetId), timeout)) {
                throw new ControlException("node " + targetId + " has no management service (its deployment has no"
                        + " <management>), so it takes no upgrade or migration requests");
            }
        } catch (InterruptedException e) {
            Thread.currentThread().interrupt();
            throw new ControlException("interrupted", e);
        }
    }

    /** {@return the id of the node the tool dialed, from its handshake} */
    String targetId() {
        return targetId;
    }

    @Override
    public void close() {
        closeBoth(Objects.requireNonNull(network, "network"), node);
    }

    /** A control request that could not be made; its message says why and what to check. */
    static final class ControlException extends Exception {

        private static final long serialVersionUID = 1L;

        ControlException(String message) {
            super(message);
        }

        ControlException(String message, Throwable cause) {
            super(message, cause);
        }
    }
}
