package io.etherware.services.network.internal;

import io.etherware.core.kernel.Kernel;
import io.etherware.core.kernel.ProfileResolutionException;
import io.etherware.core.kernel.RemoteRoute;
import io.etherware.core.message.Message;
import io.etherware.core.message.MessageId;
import io.etherware.core.message.Profile;
import io.etherware.core.message.QoS;
import io.etherware.core.message.Text;
import io.etherware.rt.platform.ThreadPolicy;
import io.etherware.services.network.CloseReason;
import io.etherware.services.network.NetworkConfig;
import io.etherware.services.network.NetworkStats;
import io.etherware.services.network.PeerStatus;
import io.etherware.services.time.NetworkTime;
import java.io.IOException;
import java.net.InetSocketAddress;
import java.net.ServerSocket;
import java.net.Socket;
import java.security.SecureRandom;
import java.time.Duration;
import java.util.ArrayList;
import java.util.Comparator;
import java.util.List;
import java.util.Optional;
import java.util.concurrent.ConcurrentHashMap;
import java.util.concurrent.ConcurrentLinkedQueue;
import java.util.concurrent.CopyOnWriteArrayList;
import java.util.concurrent.ScheduledThreadPoolExecutor;
import java.util.concurrent.TimeUnit;
import org.slf4j.Logger;
import org.slf4j.LoggerFactory;

/**
 * The machinery behind {@link io.etherware.services.network.NetworkMessenger}: the listening
 * socket and its acceptor thread, the dialers, the peers and their connections, the routes, the
 * announcements of this node's profiles, and a control thread that runs a {@link ControlTick}
 * every {@value #TICK_MS} ms for redialing, delayed acknowledgements, time probes and expiry.
 *
 * <p>Threads (all platform threads): one acceptor, one control, and per connection a reader and
 * a writer. Senders never block: on an idle connection a sender writes its frame itself, otherwise
 * it queues at a {@link Peer} (see {@link Link}).
 *
 * <p>Thread-safety: all methods may be called from any thread.
 */
public final class Engine {

    private static final Logger log = LoggerFactory.getLogger("io.etherware.services.network.NetworkMessenger");
    static final long TICK_MS = 10;
    private static final long CLOSE_DRAIN_NS = TimeUnit.SECONDS.toNanos(1);

    private final Kernel kernel;
    private final NetworkConfig config;
    private final String nodeId;
    private final long incarnation;
    private final NetworkTime networkTime;
    private final Counters counters = new Counters();
    private final RouteTable routes;
    private final ConcurrentHashMap<String, Peer> peers = new ConcurrentHashMap<>();
    private final List<Dialer> dialers = new CopyOnWriteArrayList<>();
    private final ConcurrentLinkedQueue<Profile> toReconcile = new ConcurrentLinkedQueue<>();
    private final ScheduledThreadPoolExecutor control;
    private final StateSignal stateChanged = new StateSignal();
    private final NetworkContext context;
    private final ConnectionEvents events = new Events();
    private final Admission admission;
    private final ControlTick tick;
    private ServerSocket server;
    private Thread acceptor;
    private volatile boolean closed;

    private final Announcer announcer;

    public Engine(Kernel kernel, NetworkConfig config) {
        this.kernel = kernel;
        this.config = config;
        this.nodeId = kernel.nodeId();
        this.incarnation = NetworkContext.nonZero(new SecureRandom().nextLong());
        this.networkTime = new NetworkTime(kernel.clock(), config.timeWindowSize(), NetworkTime.DEFAULT_MIN_DRIFT_SPAN);
        this.control = new ScheduledThreadPoolExecutor(1, task -> {
            Thread thread = new Thread(task, "etherware-net-" + nodeId + "-control");
            thread.setDaemon(true);
            return thread;
        });
        this.announcer = new Announcer(kernel, peers.values(), toReconcile);
        var lanes = new ArrayList<IoThreads>();
        for (int lane = 0; lane < config.lanes(); lane++) {
            lanes.add(IoThreads.of(kernel, config, lane));
        }
        var losses = new Losses(kernel, counters);
        var flushes = new RouteFlushes(kernel, control, losses, counters, config.lanes());
        this.routes = new RouteTable(kernel.registry(), config.announcePolicy(), counters.announcementsRefused, flushes,
                control);
        this.context = new NetworkContext(nodeId, incarnation, kernel, config, counters, networkTime, losses, lanes,
                control, config.codecFor(kernel), flushes);
        this.admission = new Admission(context);
        this.tick = new ControlTick(context, dialers, peers, toReconcile, routes, stateChanged);
    }

    /** The policy the reader and writer threads of {@code lane} ask for. */
    public ThreadPolicy ioThreadPolicy(int lane) {
        if (lane < 0 || lane >= config.lanes()) {
            throw new IllegalArgumentException("lane=" + lane + " must be in 0.." + (config.lanes() - 1));
        }
        return context.lanes().get(lane).policy();
    }

    // ---------------------------------------------------------------- lifecycle

    /** Binds, starts accepting and dialing, and announces this node's profiles. */
    public void start() throws IOException {
        var factory = config.connectionFactory();
        var ownId = factory.localNodeId();
        if (ownId.isPresent() && !ownId.get().equals(nodeId)) {
            throw new IOException("this node's certificate names node '" + ownId.get() + "', but the node's id is '"
                    + nodeId + "': give the node the key store made for it");
        }
        if (config.isInsecureBeyondLoopback()) {
            log.warn("node {}: INSECURE: plain TCP beyond loopback (insecure=true): peers are not authenticated and"
                    + " links are not encrypted; any host reaching {} can speak for any node", nodeId,
                    config.listenAddress());
        }
        // The codec's first use builds its serializers (tens of milliseconds): pay that now, not
        // on the first message of a control loop.
        Message warmUp = new Message(kernel.profile(), kernel.profile(), kernel.clock().epochNanos(), QoS.NONE,
                new Text("warm-up"), new MessageId(nodeId, 0), null);
        context.codec().decode(context.codec().encode(warmUp));
        announcer.start();
        server = config.connectionFactory().listen(config.listenAddress());
        acceptor = new Thread(this::acceptLoop, "etherware-net-" + nodeId + "-accept");
        acceptor.setDaemon(true);
        acceptor.start();
        for (InetSocketAddress address : config.peers()) {
            addDialers(address);
        }
        control.scheduleWithFixedDelay(tick, 0, TICK_MS, TimeUnit.MILLISECONDS);
        log.info("node {}: network messenger listening on {}, dialing {}", nodeId, localAddress(), config.peers());
    }

    /** Dials another node from now on, and keeps it connected. */
    public void addPeer(InetSocketAddress address) {
        if (closed) {
            throw new IllegalStateException("the network messenger of node '" + nodeId + "' is closed");
        }
        addDialers(address);
    }

    /** One dialer per lane: each keeps its lane's connection to the node at {@code address}. */
    private void addDialers(InetSocketAddress address) {
        for (int lane = 0; lane < config.lanes(); lane++) {
            dialers.add(new Dialer(this, address, lane));
        }
    }

    public InetSocketAddress localAddress() {
        if (server == null) {
            throw new IllegalStateException("node '" + nodeId + "': the network messenger is not listening");
        }
        return (InetSocketAddress) server.getLocalSocketAddress();
    }

    /**
     * Lets queued messages go for up to a second, says BYE on every connection, and reports what
     * could not be sent to its senders. Idempotent.
     */
    public void close() {
        if (closed) {
            return;
        }
        long deadlineNs = nowNs() + CLOSE_DRAIN_NS;
        while (hasBacklog() && nowNs() - deadlineNs < 0) {
            sleepMs(1);
        }
        closed = true;
        announcer.stop();
        control.shutdownNow();
        if (server != null) {
            try {
                server.close();
            } catch (IOException e) {
                log.debug("node {}: closing the server socket: {}", nodeId, e.toString());
            }
        }
        for (Connection connection : admission.all()) {
            connection.close(CloseReason.SHUTDOWN, "node '" + nodeId + "' is closing its network messenger");
        }
        for (Peer peer : peers.values()) {
            for (Outgoing lost : peer.close()) {
                context.losses().lost(lost.message(), "the network messenger of node '" + nodeId
                        + "' closed before sending it");
            }
            routes.forget(peer);
        }
        routes.close();
        join(acceptor);
        try {
            control.awaitTermination(1, TimeUnit.SECONDS);
        } catch (InterruptedException e) {
            Thread.currentThread().interrupt();
        }
        log.info("node {}: network messenger closed: {}", nodeId, stats());
        stateChanged.signal();
    }

    private boolean hasBacklog() {
        for (Peer peer : peers.values()) {
            for (Link link : peer.links()) {
                int[] backlog = link.backlog();
                if (link.isConnected() && backlog[0] + backlog[1] > 0) {
                    return true;
                }
            }
        }
        return false;
    }

    private void acceptLoop() {
        while (!closed) {
            Socket socket;
            try {
                socket = server.accept();
            } catch (IOException e) {
                if (!closed) {
                    log.warn("node {}: accepting a connection failed: {}", nodeId, e.toString());
                    sleepMs(TICK_MS);
                }
                continue;
            }
            Connection connection = open(socket, null);
            if (connection != null) {
                new ConnectionThread(connection, "etherware-net-" + nodeId + "-accepted-" + connection.remote()).start();
            }
        }
    }

    /**
     * A connection over {@code socket}, or null (socket closed) if we close or the connections are
     * at their limit (see {@link Admission}).
     */
    Connection open(Socket socket, Dialer dialer) {
        String refusal = closed ? "closing" : admission.refusal();
        if (refusal != null) {
            log.warn("node {}: refusing a connection from {}: {}", nodeId, socket.getRemoteSocketAddress(), refusal);
            try {
                socket.close();
            } catch (IOException e) {
                // Refused anyway.
            }
            return null;
        }
        var connection = new Connection(context, events, socket, dialer);
        admission.admit(connection);
        return connection;
    }

    // ---------------------------------------------------------------- connections

    private Peer peer(String peerId) {
        return peers.computeIfAbsent(peerId, id -> new Peer(id, context));
    }

    /** Whether every lane to {@code peerId} is connected. */
    boolean isConnected(String peerId) {
        Peer peer = peers.get(peerId);
        return peer != null && peer.isConnected();
    }

    /** Whether {@code lane} to {@code peerId} is connected. */
    boolean isConnected(String peerId, int lane) {
        Peer peer = peers.get(peerId);
        return peer != null && peer.link(lane).isConnected();
    }

    /** What the connections tell the messenger. */
    private final class Events implements ConnectionEvents {
        @Override
        public Peer peer(String nodeId) {
            return Engine.this.peer(nodeId);
        }

        @Override
        public void handshakeEnded(Connection connection) {
            admission.handshakeEnded(connection);
        }

        @Override
        public boolean activate(Connection connection, Frame.Hello hello, Frame.Resume theirs,
                                long helloArrivedEpochNs) {
            return Engine.this.activate(connection, hello, theirs, helloArrivedEpochNs);
        }

        @Override
        public void stateChanged() {
            stateChanged.signal();
        }

        @Override
        public void announced(Peer peer, long incarnation, Frame.Announce announce) {
            peer.onAnnounce(incarnation, announce.version(), () -> routes.announce(peer, announce.profiles()));
            stateChanged.signal();
        }

        @Override
        public void peerShutDown(Peer peer) {
            log.info("node {}: node '{}' is shutting down: unrouting its profiles", nodeId, peer.nodeId);
            routes.forget(peer);
            stateChanged.signal();
        }

        @Override
        public void connectionClosed(Connection connection, CloseReason reason, String detail, boolean wasActive) {
            counters.closed(reason);
            if (wasActive) {
                connection.peer().connectionEnded(NetworkContext.nowNs(), connection.endedWithoutGoodbye(reason));
            }
            if (reason.isBadInput()) {
                log.warn("node {}: closed {} for bad input: {}: {}", nodeId, connection, reason, detail);
            } else if (reason == CloseReason.SHUTDOWN || !wasActive) {
                log.debug("node {}: closed {}: {}: {}", nodeId, connection, reason, detail);
            } else {
                log.info("node {}: closed {}: {}: {}", nodeId, connection, reason, detail);
            }
        }

        @Override
        public void connectionEnded(Connection connection, boolean wasActive, CloseReason reason) {
            admission.ended(connection);
            if (connection.dialer() != null) {
                connection.dialer().ended(connection.isActivated(), reason);
            }
            if (wasActive) {
                stateChanged.signal();
            }
        }
    }

    /** After the handshake: make the connection its lane's, or close it as a duplicate. */
    private boolean activate(Connection connection, Frame.Hello hello, Frame.Resume theirs, long helloArrivedEpochNs) {
        Peer peer = connection.peer();
        Link link = connection.link();
        Peer.Activation outcome = peer.activate(connection, hello, theirs, announcer::body);
        LaneActivation activation = outcome.link();
        if (!activation.accepted()) {
            context.losses().reportLost(activation.lost(), "the streams with node '" + peer.nodeId
                    + "' disagreed; its fate is unknown");
            if (activation.refusal() != null) {
                connection.close(CloseReason.SEQUENCE_ERROR, activation.refusal());
            } else if (closed) {
                connection.close(CloseReason.SHUTDOWN, "node '" + nodeId + "' is closing its network messenger");
            } else if (link.isConnected()) {
                connection.close(CloseReason.DUPLICATE, "node '" + peer.nodeId + "' is connected already;"
                        + " keeping the connection dialed by '" + lowerId(peer.nodeId) + "'");
            } else {
                connection.close(CloseReason.IO_ERROR, "node '" + peer.nodeId + "' expired during the handshake;"
                        + " redial");
            }
            return false;
        }
        counters.opened.increment();
        if (outcome.restarted()) {
            log.info("node {}: node '{}' restarted (new incarnation)", nodeId, peer.nodeId);
            networkTime.forget(peer.nodeId);
        }
        // Every lane's handshake gives the first guess (ignored once exchanges are measured): the
        // lane that connects first may carry messages before lane 0, which has the time probes, is up.
        networkTime.onHandshake(peer.nodeId, hello.epochNs(), helloArrivedEpochNs);
        if (connection.dialer() != null) {
            connection.dialer().activated(peer.nodeId);
        }
        log.info("node {}: connected to node '{}', lane {} ({})", nodeId, peer.nodeId, connection.lane(), connection);
        if (activation.loser() != null) {
            activation.loser().close(CloseReason.DUPLICATE, "replaced by the connection dialed by '"
                    + connection.initiatorId() + "'");
        }
        context.losses().reportLost(activation.lost(), "node '" + peer.nodeId + "' restarted before acknowledging it;"
                + " it may or may not have been handled");
        stateChanged.signal();
        return true;
    }

    private String lowerId(String peerId) {
        return nodeId.compareTo(peerId) < 0 ? nodeId : peerId;
    }

    /** A route to whatever profile a peer hosts, e.g. for a migration to that node. */
    public RemoteRoute routeTo(String peerId) {
        if (!Profile.isName(peerId) || peerId.equals(nodeId)) {
            throw new IllegalArgumentException("peerId='" + peerId + "' must be another node's id");
        }
        Peer peer = peer(peerId);
        return new RemoteRoute() {
            @Override
            public void deliver(Message message) {
                peer.enqueue(message);
            }

            @Override
            public boolean isServedBy(String nodeId) {
                return nodeId.equals(peerId);
            }

            @Override
            public String toString() {
                return "network route to node '" + peerId + "'";
            }
        };
    }

    /** See {@link RouteTable#adopt}. */
    public void adoptRoute(Profile profile, RemoteRoute route, String nodeId) {
        routes.adopt(profile, route, nodeId);
    }

    // ---------------------------------------------------------------- status

    public NetworkStats stats() {
        int connected = 0;
        for (Peer peer : peers.values()) {
            if (peer.isConnected()) {
                connected++;
            }
        }
        return counters.snapshot(nodeId, connected);
    }

    public List<PeerStatus> peers() {
        var all = new ArrayList<PeerStatus>();
        for (Peer peer : peers.values()) {
            all.add(status(peer));
        }
        all.sort(Comparator.comparing(PeerStatus::nodeId));
        return all;
    }

    /** See {@link io.etherware.services.network.NetworkMessenger#goneWithoutGoodbye}: how long ago, in ns, or -1. */
    public long goneWithoutGoodbyeNs(String peerId) {
        Peer peer = peers.get(peerId);
        long since = peer == null ? -1 : peer.goneSinceNs();
        return since < 0 ? -1 : Math.max(0, NetworkContext.nowNs() - since);
    }

    public Optional<PeerStatus> peerStatus(String peerId) {
        Peer peer = peers.get(peerId);
        return peer == null ? Optional.empty() : Optional.of(status(peer));
    }

    private PeerStatus status(Peer peer) {
        Connection primary = peer.primary();
        int[] backlog = peer.backlog();
        return new PeerStatus(peer.nodeId, peer.isConnected(), Optional.ofNullable(primary).map(Connection::remote),
                backlog[0], backlog[1], routes.hostedBy(peer.nodeId), networkTime.peer(peer.nodeId));
    }

    /** Waits until every lane to {@code peerId} is connected; false on timeout. */
    public boolean awaitConnected(String peerId, Duration timeout) throws InterruptedException {
        return stateChanged.await(timeout, () -> isConnected(peerId));
    }

    /** Waits until {@code profile} resolves on this node; false on timeout. */
    public boolean awaitResolvable(Profile profile, Duration timeout) throws InterruptedException {
        return stateChanged.await(timeout, () -> {
            try {
                kernel.registry().resolve(profile);
                return true;
            } catch (ProfileResolutionException e) {
                return false;
            }
        });
    }

    // ---------------------------------------------------------------- shared parts

    String nodeId() {
        return nodeId;
    }

    long nowNs() {
        return NetworkContext.nowNs();
    }

    NetworkConfig config() {
        return config;
    }

    public NetworkTime networkTime() {
        return networkTime;
    }

    private static void join(Thread thread) {
        if (thread == null) {
            return;
        }
        try {
            thread.join(TimeUnit.SECONDS.toMillis(1));
        } catch (InterruptedException e) {
            Thread.currentThread().interrupt();
        }
    }

    private static void sleepMs(long ms) {
        try {
            Thread.sleep(ms);
        } catch (InterruptedException e) {
            Thread.currentThread().interrupt();
        }
    }
}
