package io.etherware.services.network;

import io.etherware.core.codec.MessageCodec;
import io.etherware.rt.platform.CpuSet;
import io.etherware.rt.platform.ThreadPolicy;
import io.etherware.services.time.NetworkTime;
import java.net.InetAddress;
import java.net.InetSocketAddress;
import java.time.Duration;
import java.util.ArrayList;
import java.util.List;
import java.util.Objects;

/**
 * The configuration of a {@link NetworkMessenger}, validated once when built; every default is
 * listed in {@link Builder}. Immutable.
 *
 * @param listenAddress             where to accept connections from other nodes (port 0: any free
 *                                  port, see {@link NetworkMessenger#localAddress()})
 * @param peers                     the nodes to dial and keep dialing
 * @param connectionFactory         makes the sockets (the TLS seam)
 * @param codec                     encodes and decodes messages; its contents types must match the
 *                                  peers'. Null (the default): a codec over the node's contents
 *                                  types ({@code Kernel.contentsTypes()}) whose document limit fits
 *                                  the frame limit, made when the messenger starts
 * @param maxFrameBytes             largest frame accepted from a peer (and sent to one)
 * @param queueCapacity             messages waiting per peer before the least critical are dropped
 * @param windowMessages            messages written to a peer and not yet acknowledged, at most
 * @param heartbeatIntervalNs       a frame is sent at least this often on an idle connection
 * @param heartbeatTimeoutNs        a connection on which nothing arrives this long is closed
 * @param handshakeTimeoutNs        a connection must complete its handshake within this
 * @param connectTimeoutNs          a dial gives up after this
 * @param reconnectInitialBackoffNs first delay before redialing a lost or refused peer
 * @param reconnectMaxBackoffNs     the delay doubles up to this
 * @param reconnectJitter           each delay is lowered by a random part of up to this fraction
 * @param peerDownGraceNs           how long messages for a disconnected peer wait for it to come
 *                                  back before they are reported undeliverable and its profiles
 *                                  are unrouted
 * @param timeProbeIntervalNs       NetworkTime exchanges per peer, after the burst at connection
 * @param timeProbeBurst            exchanges in quick succession when a connection opens
 * @param timeWindowSize            exchanges NetworkTime's filter looks at
 * @param maxConnections            established connections beyond which new ones are refused
 * @param maxHops                   relays a message may make through nodes whose routes point on
 *                                  (during a migration) before it is undeliverable
 * @param maxPendingHandshakes      connections in their handshake at once; a new one beyond this
 *                                  closes the oldest pending one, so a flood of idle connections
 *                                  cannot lock honest peers out (established connections count
 *                                  against {@code maxConnections} only)
 * @param maxQueuedBytesPerPeer     bytes of encoded messages waiting for a peer or written and not
 *                                  yet acknowledged by it; beyond this, messages to it are shed or
 *                                  refused like those beyond {@code queueCapacity}
 * @param maxInboundBytesPerPeer    bytes of a peer's messages this node holds in its queues (not yet
 *                                  handled or passed on) beyond which it stops reading from that
 *                                  peer until they drain: TCP then slows the peer down
 * @param announcePolicy            which application profiles a peer may announce here
 * @param threadPolicy              the OS policy and priority of the reader and writer threads of
 *                                  lane 0 (HIGH and MIDDLE messages; every message with one lane), or
 *                                  null for the default: with a {@link
 *                                  io.etherware.rt.scheduling.RealtimeScheduler}, SCHED_FIFO one level
 *                                  above its highest dispatcher (so a thread that carries HIGH
 *                                  messages never waits for LOW work), otherwise ordinary threads
 * @param bulkThreadPolicy          the same for lane 1 (LOW and NONE messages), or null for the
 *                                  default: with a {@code RealtimeScheduler}, SCHED_FIFO one level
 *                                  above its lowest real-time dispatcher (LOW traffic never runs
 *                                  above MIDDLE or HIGH work), otherwise ordinary threads
 * @param cpus                      the CPUs of the reader and writer threads
 * @param lanes                     connections per pair of nodes: 2 (default) carries HIGH and MIDDLE
 *                                  messages on one and LOW and NONE on the other, each with its own
 *                                  stream, queue and threads, so a HIGH message never waits behind
 *                                  LOW bytes; 1 carries everything on one (both nodes must agree)
 * @param insecure                  whether plain, unauthenticated links beyond loopback were chosen
 *                                  on purpose ({@link Builder#insecure}); without it a messenger
 *                                  whose factory does not authenticate peers only listens on and
 *                                  dials loopback addresses
 */
public record NetworkConfig(InetSocketAddress listenAddress, List<InetSocketAddress> peers,
                            ConnectionFactory connectionFactory, MessageCodec codec, int maxFrameBytes,
                            int queueCapacity, int windowMessages, long heartbeatIntervalNs, long heartbeatTimeoutNs,
                            long handshakeTimeoutNs, long connectTimeoutNs, long reconnectInitialBackoffNs,
                            long reconnectMaxBackoffNs, double reconnectJitter, long peerDownGraceNs,
                            long timeProbeIntervalNs, int timeProbeBurst, int timeWindowSize, int maxConnections,
                            int maxHops, int maxPendingHandshakes, long maxQueuedBytesPerPeer,
                            long maxInboundBytesPerPeer, AnnouncePolicy announcePolicy, ThreadPolicy threadPolicy,
                            ThreadPolicy bulkThreadPolicy, CpuSet cpus, boolean insecure, int lanes) {

    /** Default {@link #maxFrameBytes}: 1 MiB. */
    public static final int DEFAULT_MAX_FRAME_BYTES = 1 << 20;
    /** Smallest {@link #maxFrameBytes}: room for a handshake and a small message. */
    public static final int MIN_FRAME_BYTES = 4096;
    /** Smallest document limit of a {@link #codec()} given: what peers require of a node's frames. */
    public static final int MIN_CODEC_DOCUMENT_BYTES = 1024;

    /**
     * The codec a messenger for {@code kernel} uses: {@link #codec()} if one was given, else one over
     * the node's contents types whose document limit fits {@link #maxFrameBytes()}.
     *
     * @param kernel the node the messenger serves
     * @return the codec
     */
    public MessageCodec codecFor(io.etherware.core.kernel.Kernel kernel) {
        return codec != null ? codec
                : MessageCodec.builder().contentsTypes(kernel.contentsTypes()).maxDocumentBytes(maxFrameBytes - 64).build();
    }

    /**
     * Checks every field and their relations; the bounds are listed on the {@link Builder}'s
     * setters.
     *
     * @throws NullPointerException     if a required field is null, naming it and the usual value
     * @throws IllegalArgumentException naming the field, its value and the valid range, or, for a
     *                                  factory that does not authenticate peers without
     *                                  {@code insecure}, the first address beyond loopback
     */
    public NetworkConfig {
        Objects.requireNonNull(listenAddress, "listenAddress=null: e.g. listen(new InetSocketAddress(\"0.0.0.0\", 7400))");
        peers = List.copyOf(Objects.requireNonNull(peers, "peers=null"));
        Objects.requireNonNull(connectionFactory, "connectionFactory=null: use ConnectionFactory.plain()");
        NetworkConfigChecks.frames(maxFrameBytes, queueCapacity, windowMessages);
        NetworkConfigChecks.codec(codec);
        NetworkConfigChecks.heartbeats(heartbeatIntervalNs, heartbeatTimeoutNs);
        NetworkConfigChecks.dialing(handshakeTimeoutNs, connectTimeoutNs, reconnectInitialBackoffNs,
                reconnectMaxBackoffNs, reconnectJitter, peerDownGraceNs);
        NetworkConfigChecks.timeProbes(timeProbeIntervalNs, timeProbeBurst, timeWindowSize);
        NetworkConfigChecks.limits(maxConnections, maxHops, maxPendingHandshakes, maxFrameBytes, maxQueuedBytesPerPeer,
                maxInboundBytesPerPeer);
        Objects.requireNonNull(announcePolicy, "announcePolicy=null: use AnnouncePolicy.any()");
        Objects.requireNonNull(cpus, "cpus=null: use CpuSet.inherit()");
        NetworkConfigChecks.threads(threadPolicy, bulkThreadPolicy, lanes);
        if (!connectionFactory.authenticatesPeers() && !insecure) {
            NetworkConfigChecks.loopbackOnly(listenAddress, peers);
        }
    }

    /**
     * Whether links of this configuration go beyond loopback without authentication (which only
     * {@link Builder#insecure} allows); the messenger warns when it starts so.
     *
     * @return true if the factory does not authenticate peers and the listen address or a peer is
     *         not a loopback address
     */
    public boolean isInsecureBeyondLoopback() {
        return !connectionFactory.authenticatesPeers()
                && NetworkConfigChecks.anyBeyondLoopback(listenAddress, peers);
    }

    /**
     * A builder holding the defaults.
     *
     * @return a new builder; see {@link Builder} for the defaults
     */
    public static Builder builder() {
        return new Builder();
    }

    /**
     * Builds a {@link NetworkConfig}. Defaults: listen on the loopback interface, any free port;
     * no peers; plain TCP; a {@link MessageCodec} over the node's contents types whose document
     * limit fits the frame limit; frames up to 1 MiB; 10,000 queued messages and 1,024
     * unacknowledged per peer; heartbeat every 500 ms, dead after 3 s of silence; handshake within
     * 2 s, dial within 2 s; redial after 50 ms doubling to 5 s, with 20 % jitter; a peer down for
     * 10 s loses its messages and routes; NetworkTime burst of 8 exchanges, then one per second,
     * filter window {@value NetworkTime#DEFAULT_WINDOW_SIZE}; 64 connections, of which 16 in their
     * handshake; 4 relays; 64 MiB queued or unacknowledged per peer, 64 MiB of a peer's messages
     * held here; any peer may announce any application profile; two lanes per pair of nodes, the
     * reader and writer threads of lane 0 one real-time level above the highest dispatcher of a
     * real-time scheduler and those of lane 1 one level above its lowest real-time dispatcher
     * (ordinary threads with another scheduler), every CPU; not insecure (plain TCP only on
     * loopback). Queue bounds ({@code queueCapacity}, {@code windowMessages},
     * {@code maxQueuedBytesPerPeer}) hold for each lane.
     *
     * <p>Not thread-safe; use it on one thread.
     */
    public static final class Builder {
        private InetSocketAddress listenAddress = new InetSocketAddress(InetAddress.getLoopbackAddress(), 0);
        private final List<InetSocketAddress> peers = new ArrayList<>();
        private ConnectionFactory connectionFactory = ConnectionFactory.plain();
        private MessageCodec codec;
        private int maxFrameBytes = DEFAULT_MAX_FRAME_BYTES;
        private int queueCapacity = 10_000;
        private int windowMessages = 1024;
        private long heartbeatIntervalNs = Duration.ofMillis(500).toNanos();
        private long heartbeatTimeoutNs = Duration.ofSeconds(3).toNanos();
        private long handshakeTimeoutNs = Duration.ofSeconds(2).toNanos();
        private long connectTimeoutNs = Duration.ofSeconds(2).toNanos();
        private long reconnectInitialBackoffNs = Duration.ofMillis(50).toNanos();
        private long reconnectMaxBackoffNs = Duration.ofSeconds(5).toNanos();
        private double reconnectJitter = 0.2;
        private long peerDownGraceNs = Duration.ofSeconds(10).toNanos();
        private long timeProbeIntervalNs = Duration.ofSeconds(1).toNanos();
        private int timeProbeBurst = 8;
        private int timeWindowSize = NetworkTime.DEFAULT_WINDOW_SIZE;
        private int maxConnections = 64;
        private int maxHops = 4;
        private int maxPendingHandshakes = 16;
        private long maxQueuedBytesPerPeer = 64L << 20;
        private long maxInboundBytesPerPeer = 64L << 20;
        private AnnouncePolicy announcePolicy = AnnouncePolicy.any();
        private ThreadPolicy threadPolicy;
        private ThreadPolicy bulkThreadPolicy;
        private CpuSet cpus = CpuSet.inherit();
        private boolean insecure;
        private int lanes = 2;

        Builder() {
        }

        /**
         * Where to accept connections from other nodes. Default: the loopback address, any free
         * port. Beyond loopback it needs an authenticating factory or {@link #insecure}.
         *
         * @param value the address to bind; port 0 for any free port (see
         *              {@link NetworkMessenger#localAddress()}); not null (checked by {@link #build()})
         * @return this builder
         */
        public Builder listen(InetSocketAddress value) {
            listenAddress = value;
            return this;
        }

        /**
         * Where to accept connections: {@code host:port}, e.g. {@code listen("0.0.0.0", 7400)} for
         * every interface. The host name is looked up now.
         *
         * @param host the interface's address or host name
         * @param port the port, 0..65535 (0: any free port)
         * @return this builder
         * @throws IllegalArgumentException if {@code port} is out of range or {@code host} is null
         */
        public Builder listen(String host, int port) {
            return listen(new InetSocketAddress(host, port));
        }

        /**
         * A node to dial and keep connected; may be called for several nodes. Default: none (the
         * node only accepts). Beyond loopback it needs an authenticating factory or
         * {@link #insecure}.
         *
         * @param value the peer's listen address
         * @return this builder
         * @throws NullPointerException if {@code value} is null
         */
        public Builder peer(InetSocketAddress value) {
            peers.add(Objects.requireNonNull(value, "peer"));
            return this;
        }

        /**
         * A node to dial and keep connected: {@code host:port}. The host name is looked up now.
         *
         * @param host the peer's address or host name
         * @param port its listen port, 0..65535
         * @return this builder
         * @throws IllegalArgumentException if {@code port} is out of range or {@code host} is null
         */
        public Builder peer(String host, int port) {
            return peer(new InetSocketAddress(host, port));
        }

        /**
         * How sockets are made and peers authenticated. Default {@link ConnectionFactory#plain()},
         * which authenticates nobody and is therefore limited to loopback unless {@link #insecure}.
         *
         * @param value e.g. {@link ConnectionFactory#tls}; not null (checked by {@link #build()})
         * @return this builder
         */
        public Builder connectionFactory(ConnectionFactory value) {
            connectionFactory = value;
            return this;
        }

        /**
         * How messages are encoded on the wire. Default: a {@link MessageCodec} with a document
         * limit of {@code maxFrameBytes - 64}, so every message that encodes fits a frame, over the
         * node's contents types ({@code Kernel.contentsTypes()}), made when the messenger starts.
         * A codec with a lower limit lowers the largest frame the node says it takes in its HELLO,
         * so that peers refuse a message too large for it at their sender, not on the wire.
         * A codec given here keeps its own registry: build it over the node's
         * ({@code MessageCodec.builder().contentsTypes(node.contentsTypes())}), or the kernel's
         * notices and the services' messages will not cross.
         *
         * @param value the codec, or null for the default; its contents types must include every
         *              contents type sent across and match the peers'; its document limit at least
         *              {@link #MIN_CODEC_DOCUMENT_BYTES} (checked by {@link #build()})
         * @return this builder
         */
        public Builder codec(MessageCodec value) {
            codec = value;
            return this;
        }

        /**
         * The largest frame accepted from a peer and sent to one; a longer one from a peer closes
         * the connection ({@link CloseReason#OVERSIZE_FRAME}). Default
         * {@value #DEFAULT_MAX_FRAME_BYTES} (1 MiB).
         *
         * @param value bytes, {@value #MIN_FRAME_BYTES} to 256 MiB; at most half of
         *              {@code maxQueuedBytesPerPeer} and of {@code maxInboundBytesPerPeer}
         * @return this builder
         */
        public Builder maxFrameBytes(int value) {
            maxFrameBytes = value;
            return this;
        }

        /**
         * Messages waiting for one peer (per lane). When full, a new message evicts the oldest of a
         * lower criticality, or is refused when there is none; NONE and LOW messages dropped so
         * are only counted, others are reported to their senders as undeliverable. Default 10,000.
         *
         * @param value messages, 1 to 10,000,000
         * @return this builder
         */
        public Builder queueCapacity(int value) {
            queueCapacity = value;
            return this;
        }

        /**
         * Messages written to one peer (per lane) and not yet acknowledged by its kernel, at most;
         * beyond them, messages wait in the queue. Default 1,024.
         *
         * @param value messages, 4 to 1,048,576
         * @return this builder
         */
        public Builder windowMessages(int value) {
            windowMessages = value;
            return this;
        }

        /**
         * On an idle connection, a frame (a heartbeat) is sent at least this often, so the peer
         * can tell a quiet link from a dead one. Default 500 ms.
         *
         * @param value &gt; 0, and at most half the heartbeat timeout
         * @return this builder
         */
        public Builder heartbeatInterval(Duration value) {
            heartbeatIntervalNs = value.toNanos();
            return this;
        }

        /**
         * How long a connection may stay silent (or its peer not read) before it is closed
         * ({@link CloseReason#HEARTBEAT_TIMEOUT}, {@link CloseReason#NOT_READING}). Default 3 s.
         *
         * @param value at least twice the heartbeat interval, or a healthy idle peer looks dead
         * @return this builder
         */
        public Builder heartbeatTimeout(Duration value) {
            heartbeatTimeoutNs = value.toNanos();
            return this;
        }

        /**
         * How long a new connection has to complete its handshake (TLS included) before it is
         * closed ({@link CloseReason#HANDSHAKE_TIMEOUT}). Default 2 s.
         *
         * @param value &gt; 0
         * @return this builder
         */
        public Builder handshakeTimeout(Duration value) {
            handshakeTimeoutNs = value.toNanos();
            return this;
        }

        /**
         * How long a dial waits for the TCP connection before it gives up and backs off. Default
         * 2 s.
         *
         * @param value &gt; 0; used in whole milliseconds (at least 1)
         * @return this builder
         */
        public Builder connectTimeout(Duration value) {
            connectTimeoutNs = value.toNanos();
            return this;
        }

        /**
         * Redial delays after a lost or refused connection: {@code initial}, doubling up to
         * {@code max}, each lowered by a random part of up to {@code jitter}. Default 50 ms
         * doubling to 5 s, jitter 0.2.
         *
         * @param initial the first delay, &gt; 0
         * @param max     the largest delay, at least {@code initial}
         * @param jitter  the fraction a delay may be lowered by, in [0, 1)
         * @return this builder
         */
        public Builder reconnectBackoff(Duration initial, Duration max, double jitter) {
            reconnectInitialBackoffNs = initial.toNanos();
            reconnectMaxBackoffNs = max.toNanos();
            reconnectJitter = jitter;
            return this;
        }

        /**
         * How long messages for a disconnected peer wait for it to come back before they are
         * reported undeliverable and its profiles are unrouted. Default 10 s.
         *
         * @param value &gt; 0
         * @return this builder
         */
        public Builder peerDownGrace(Duration value) {
            peerDownGraceNs = value.toNanos();
            return this;
        }

        /**
         * NetworkTime: {@code burst} exchanges at connection, then one every {@code interval}.
         * Default 8 exchanges, then one per second.
         *
         * @param interval the time between exchanges with one peer, &gt; 0
         * @param burst    exchanges in quick succession when a connection opens, 0 to 64
         * @return this builder
         */
        public Builder timeProbes(Duration interval, int burst) {
            timeProbeIntervalNs = interval.toNanos();
            timeProbeBurst = burst;
            return this;
        }

        /**
         * How many of a peer's latest exchanges NetworkTime's filter looks at. Default
         * {@value NetworkTime#DEFAULT_WINDOW_SIZE}.
         *
         * @param value exchanges, 1 to 1,024
         * @return this builder
         */
        public Builder timeWindowSize(int value) {
            timeWindowSize = value;
            return this;
        }

        /**
         * Established connections (all lanes, all peers) beyond which new ones are refused.
         * Default 64.
         *
         * @param value connections, 1 to 100,000
         * @return this builder
         */
        public Builder maxConnections(int value) {
            maxConnections = value;
            return this;
        }

        /**
         * How many times a message may be relayed through nodes whose routes point on (during a
         * migration) before it is undeliverable. Default 4.
         *
         * @param value relays, 0 to 32 (0: never relayed)
         * @return this builder
         */
        public Builder maxHops(int value) {
            maxHops = value;
            return this;
        }

        /**
         * Connections in their handshake at once; a new one beyond this closes the oldest pending
         * one ({@link CloseReason#HANDSHAKE_EVICTED}). Default 16.
         *
         * @param value connections, 1 to 100,000
         * @return this builder
         */
        public Builder maxPendingHandshakes(int value) {
            maxPendingHandshakes = value;
            return this;
        }

        /**
         * Bytes of encoded messages waiting for, or unacknowledged by, one peer (per lane) before
         * its messages are shed or refused like those beyond {@code queueCapacity}. Default 64 MiB.
         *
         * @param value bytes, from twice {@code maxFrameBytes} to 2^40
         * @return this builder
         */
        public Builder maxQueuedBytesPerPeer(long value) {
            maxQueuedBytesPerPeer = value;
            return this;
        }

        /**
         * Bytes of one peer's messages held in this node's queues (not yet handled or passed on)
         * before it stops reading from that peer until they drain, so TCP slows the peer down.
         * Default 64 MiB.
         *
         * @param value bytes, from twice {@code maxFrameBytes} to 2^40
         * @return this builder
         */
        public Builder maxInboundBytesPerPeer(long value) {
            maxInboundBytesPerPeer = value;
            return this;
        }

        /**
         * The OS policy and priority of every lane's reader and writer threads ({@link
         * ThreadPolicy#NON_REALTIME} for ordinary threads), instead of the defaults that follow the
         * node's scheduler; {@link #bulkLaneThreads} then sets lane 1's apart.
         *
         * @param policy the policy; a real-time priority must be in 1..99 (checked by
         *               {@link #build()})
         * @return this builder
         * @throws NullPointerException if {@code policy} is null
         */
        public Builder threads(ThreadPolicy policy) {
            threadPolicy = Objects.requireNonNull(policy, "policy");
            bulkThreadPolicy = policy;
            return this;
        }

        /**
         * The OS policy and priority of lane 1's (LOW and NONE messages) reader and writer threads,
         * instead of the default: one real-time level above the lowest real-time dispatcher of a
         * {@code RealtimeScheduler}, otherwise ordinary threads. Call it after {@link #threads}.
         *
         * @param policy the policy; a real-time priority must be in 1..99 (checked by
         *               {@link #build()})
         * @return this builder
         * @throws NullPointerException if {@code policy} is null
         */
        public Builder bulkLaneThreads(ThreadPolicy policy) {
            bulkThreadPolicy = Objects.requireNonNull(policy, "policy");
            return this;
        }

        /**
         * Connections per pair of nodes, 1 or 2 (default 2: HIGH and MIDDLE messages on lane 0, LOW
         * and NONE on lane 1). Every node of a deployment must use the same number: a peer with
         * another is refused at the handshake.
         *
         * @param value 1 or 2
         * @return this builder
         */
        public Builder lanes(int value) {
            lanes = value;
            return this;
        }

        /**
         * The CPUs of the reader and writer threads. Do not pin ordinary (non-real-time) threads
         * to CPUs where real-time threads work: starved there, a Java thread can hold the whole
         * JVM at a safepoint (seen with a SCHED_FIFO dispatcher spinning for the safepoint while
         * the pinned ordinary thread it waited for never ran).
         *
         * @param value the CPUs, or {@link CpuSet#inherit()} (default) to leave the affinity as
         *              inherited; not null (checked by {@link #build()})
         * @return this builder
         */
        public Builder threadCpus(CpuSet value) {
            cpus = value;
            return this;
        }

        /**
         * Which application profiles peers may announce to this node. Default
         * {@link AnnouncePolicy#any()}.
         *
         * @param value the policy; not null (checked by {@link #build()})
         * @return this builder
         */
        public Builder announcePolicy(AnnouncePolicy value) {
            announcePolicy = value;
            return this;
        }

        /**
         * Chooses plain TCP links beyond loopback on purpose: no peer is authenticated, so any host
         * that reaches the port can speak for any node. Only for an isolated network; the
         * messenger logs a warning when it starts so.
         *
         * @param value true to allow plain links beyond loopback; default false
         * @return this builder
         */
        public Builder insecure(boolean value) {
            insecure = value;
            return this;
        }

        /**
         * The validated configuration. The builder may be used again afterwards.
         *
         * @return the configuration
         * @throws NullPointerException     if a required setting was set to null, naming it
         * @throws IllegalArgumentException naming the first setting out of range, its value and the
         *                                  range (see each setter)
         */
        public NetworkConfig build() {
            return new NetworkConfig(listenAddress, peers, connectionFactory, codec, maxFrameBytes,
                    queueCapacity, windowMessages, heartbeatIntervalNs, heartbeatTimeoutNs, handshakeTimeoutNs,
                    connectTimeoutNs, reconnectInitialBackoffNs, reconnectMaxBackoffNs, reconnectJitter, peerDownGraceNs,
                    timeProbeIntervalNs, timeProbeBurst, timeWindowSize, maxConnections, maxHops, maxPendingHandshakes,
                    maxQueuedBytesPerPeer, maxInboundBytesPerPeer, announcePolicy, threadPolicy, bulkThreadPolicy, cpus,
                    insecure, lanes);
        }
    }
}
