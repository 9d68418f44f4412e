package io.etherware.services.network;

import io.etherware.core.kernel.EtherwareNode;
import io.etherware.core.kernel.Kernel;
import io.etherware.core.kernel.RemoteRoute;
import io.etherware.core.message.Profile;
import io.etherware.rt.platform.ThreadPolicy;
import io.etherware.services.network.internal.Engine;
import io.etherware.services.time.NetworkTime;
import java.io.IOException;
import java.io.UncheckedIOException;
import java.net.InetSocketAddress;
import java.time.Duration;
import java.util.List;
import java.util.Objects;
import java.util.Optional;

/**
 * The NetworkMessenger service (paper Section III-C): joins this node to other nodes over TCP so
 * that a component sends to a profile hosted elsewhere exactly as to a local one.
 *
 * <pre>{@code
 * try (EtherwareNode node = EtherwareNode.builder().nodeId("plant-1").build().start();
 *      NetworkMessenger net = NetworkMessenger.start(node, NetworkConfig.builder()
 *              .listen("0.0.0.0", 7400).peer("controller-host", 7400).build())) {
 *     net.awaitResolvable(Profile.of("controller"), Duration.ofSeconds(5));
 *     node.send(Profile.of("controller"), new Text("hello"));
 * }
 * }</pre>
 *
 * <p>What it does. Two TCP connections per pair of nodes by default, the lanes (when both dial, the
 * connection dialed by the lower node id is kept), with TCP_NODELAY: lane 0 carries HIGH and
 * MIDDLE messages, lane 1 LOW and NONE, each with its own streams, queue and threads, so a HIGH
 * message never waits behind LOW bytes on the wire ({@link NetworkConfig#lanes()} 1: one
 * connection). Messages of one lane keep their order, and a NONE message goes after everything
 * queued before it for the same node; other messages of different lanes have no order between
 * them (the dispatchers reorder by criticality anyway). Frames of a length, a type and a body, the
 * messages themselves as the XML of {@link io.etherware.core.codec.MessageCodec} (see
 * {@code NETWORK-PROTOCOL.md}). Each node announces the profiles it hosts when a connection opens
 * and whenever they change; the others register a route for each in their registry, so
 * {@code send} and requests just work, with the message's QoS unchanged on the receiving node.
 * Messages to a peer wait in a bounded queue, most critical first; they are numbered and kept
 * until the peer's kernel acknowledges them, so a lost connection loses nothing: the next one
 * resumes where the peer stands. What cannot be delivered (peer restarted before acknowledging,
 * gone for longer than the grace period, queue full of more critical messages) is reported to
 * its sender as {@code undeliverable} (a request fails), except NONE and LOW messages shed from a
 * full queue, which are counted. Time stamps of arriving messages are translated into this
 * node's clock by {@link #networkTime()}.
 *
 * <p>Threading contract: every method may be called from any thread. Sending through the routes
 * never blocks: the sending thread encodes the message; on an idle connection it writes the frame
 * itself (which the acknowledged-stream bookkeeping proves cannot block), otherwise it queues. The
 * messenger runs on platform threads of its own: an acceptor, a control thread, and a reader and a
 * writer per connection, so a slow or dead peer holds up nobody else. A connection's reader
 * decodes each message and hands it to the kernel, which queues it for a dispatcher, or, for a
 * reply to a request whose requester waits on its future, completes that future on the reader
 * thread itself. Once a connection is established its reader and writer run at its lane's
 * {@link #ioThreadPolicy(int)}: by default lane 0 above the node's dispatchers, so LOW work never
 * holds up the threads that carry HIGH messages, and lane 1 just above the LOW dispatcher, so LOW
 * traffic never holds up MIDDLE or HIGH work. Start the node before the messenger
 * (messages may arrive at once) and close the messenger before the node; a node that closes
 * first closes its messenger too.
 */
public final class NetworkMessenger implements AutoCloseable {

    private final Engine engine;
    private final NetworkConfig config;

    private NetworkMessenger(Engine engine, NetworkConfig config) {
        this.engine = engine;
        this.config = config;
    }

    /**
     * Starts a messenger for {@code kernel}: binds the listen address, dials the peers. Returns
     * once it listens; connections come up in the background ({@link #awaitConnected}).
     *
     * @param kernel the node to join to others; the messenger closes when the node closes
     * @param config the validated configuration
     * @return the running messenger
     * @throws UncheckedIOException if the listen address cannot be bound, or the factory's
     *                              credentials name another node than {@code kernel}'s
     */
    public static NetworkMessenger start(Kernel kernel, NetworkConfig config) {
        Objects.requireNonNull(kernel, "kernel");
        Objects.requireNonNull(config, "config");
        var engine = new Engine(kernel, config);
        try {
            engine.start();
        } catch (IOException e) {
            engine.close();
            throw new UncheckedIOException("node '" + kernel.nodeId() + "': cannot listen on "
                    + config.listenAddress() + ": " + e.getMessage(), e);
        }
        var messenger = new NetworkMessenger(engine, config);
        // A node closed first takes its messenger along (off the closing thread).
        kernel.closedFuture().thenRunAsync(messenger::close, task -> Thread.ofPlatform().daemon()
                .name("etherware-net-" + kernel.nodeId() + "-close").start(task));
        return messenger;
    }

    /**
     * The configuration this messenger was started with.
     *
     * @return the configuration, as validated
     */
    public NetworkConfig config() {
        return config;
    }

    /**
     * The address this node accepts connections on.
     *
     * @return the bound address, with the actual port if 0 was configured
     */
    public InetSocketAddress localAddress() {
        return engine.localAddress();
    }

    /**
     * Dials another node from now on and keeps it connected (one connection per lane). Does not
     * wait for the connection.
     *
     * @param address the other node's listen address
     * @throws IllegalStateException if the messenger is closed
     */
    public void addPeer(InetSocketAddress address) {
        engine.addPeer(Objects.requireNonNull(address, "address"));
    }

    /**
     * Waits until node {@code nodeId} is connected, every lane. Blocks the caller: not for a
     * dispatcher thread.
     *
     * @param nodeId  the other node's id
     * @param timeout how long to wait at most
     * @return true once connected, false on timeout
     * @throws InterruptedException if the caller is interrupted while waiting
     */
    public boolean awaitConnected(String nodeId, Duration timeout) throws InterruptedException {
        return engine.awaitConnected(nodeId, timeout);
    }

    /**
     * Waits until {@code profile} resolves on this node (locally, or announced by a peer). Blocks
     * the caller: not for a dispatcher thread.
     *
     * @param profile the profile, exact or a query
     * @param timeout how long to wait at most
     * @return true once it resolves, false on timeout
     * @throws InterruptedException if the caller is interrupted while waiting
     */
    public boolean awaitResolvable(Profile profile, Duration timeout) throws InterruptedException {
        return engine.awaitResolvable(profile, timeout);
    }

    /**
     * How long ago the process of node {@code nodeId} left without a goodbye, if it did: its last
     * connection ended by end of stream or a socket error with no BYE before it, and no connection
     * of the same process (its incarnation) has come since; one of a restarted process may have.
     * That is how the end of a process looks (its system closes its sockets), or a reset by its
     * host; a node that closes its messenger says BYE first, and a partition ends connections by
     * heartbeat timeout, so neither counts. A live node whose connection was reset redials (or is
     * redialed) within a few redial delays, so a wait of that much more tells the two apart, except
     * in a partition that begins with a reset. Empty for a node not known here, or forgotten after
     * {@link NetworkConfig#peerDownGraceNs()}.
     *
     * @param nodeId the other node's id
     * @return how long ago it left so, or empty
     */
    public Optional<Duration> goneWithoutGoodbye(String nodeId) {
        long agoNs = engine.goneWithoutGoodbyeNs(Objects.requireNonNull(nodeId, "nodeId"));
        return agoNs < 0 ? Optional.empty() : Optional.of(Duration.ofNanos(agoNs));
    }

    /**
     * The peers known to this node, connected or not.
     *
     * @return a snapshot of each, sorted by node id
     */
    public List<PeerStatus> peers() {
        return engine.peers();
    }

    /**
     * One peer, if known.
     *
     * @param nodeId the peer's node id
     * @return a snapshot of it, or empty if it is not among {@link #peers()}
     */
    public Optional<PeerStatus> peer(String nodeId) {
        return engine.peerStatus(nodeId);
    }

    /**
     * A route to node {@code nodeId} for any profile, e.g. to relocate a component there
     * ({@link io.etherware.core.kernel.ComponentHost#relocateAsync}). Its messages wait for the node like any other.
     *
     * @param nodeId another node's id
     * @return a route that queues messages for that node
     * @throws IllegalArgumentException if {@code nodeId} is not a valid node id or is this node's
     */
    public RemoteRoute routeTo(String nodeId) {
        return engine.routeTo(nodeId);
    }

    /**
     * For a migration away from this node: {@code profile} is registered to {@code route} (built
     * on {@link #routeTo}{@code (nodeId)}); from the moment the announcements route the profile to
     * that same node, route it as any announced profile instead, so that it follows the component
     * if it moves on. The switch is one step and keeps each sender's order.
     *
     * @param profile the exact profile of the component that moved
     * @param route   the route registered for it now; if another is registered by then, nothing changes
     * @param nodeId  the node {@code route} leads to
     */
    public void followAnnouncements(Profile profile, RemoteRoute route, String nodeId) {
        engine.adoptRoute(Objects.requireNonNull(profile, "profile"), Objects.requireNonNull(route, "route"),
                Objects.requireNonNull(nodeId, "nodeId"));
    }

    /**
     * The clock offsets to the peers, and the time stamp translation.
     *
     * @return this messenger's NetworkTime, fed by its exchanges
     */
    public NetworkTime networkTime() {
        return engine.networkTime();
    }

    /**
     * The OS policy the reader and writer threads of lane 0 (HIGH and MIDDLE messages) ask for; see
     * {@link #ioThreadPolicy(int)}.
     *
     * @return {@code ioThreadPolicy(0)}
     */
    public ThreadPolicy ioThreadPolicy() {
        return engine.ioThreadPolicy(0);
    }

    /**
     * The OS policy the reader and writer threads of {@code lane} ask for: {@link
     * NetworkConfig#threadPolicy()} (lane 0) or {@link NetworkConfig#bulkThreadPolicy()} (lane 1),
     * or by default, with the node's {@code RealtimeScheduler}, one real-time level above its
     * highest dispatcher (lane 0) or its lowest real-time one (lane 1); ordinary threads with
     * another scheduler.
     *
     * @param lane 0, or 1 when {@link NetworkConfig#lanes()} is 2
     * @return the policy requested (the OS may refuse it; the platform then warns once)
     * @throws IllegalArgumentException if there is no such lane
     */
    public ThreadPolicy ioThreadPolicy(int lane) {
        return engine.ioThreadPolicy(lane);
    }

    /**
     * The counters now.
     *
     * @return a snapshot; each counter exact, not read atomically together
     */
    public NetworkStats stats() {
        return engine.stats();
    }

    /**
     * Lets queued messages go for up to a second, closes every connection (saying BYE), unroutes
     * the peers' profiles and reports unsent messages to their senders. Idempotent.
     */
    @Override
    public void close() {
        engine.close();
    }

    @Override
    public String toString() {
        return "NetworkMessenger[" + engine.localAddress() + "]";
    }
}
