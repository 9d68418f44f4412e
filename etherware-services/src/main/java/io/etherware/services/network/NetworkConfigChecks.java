package io.etherware.services.network;

import io.etherware.core.codec.MessageCodec;
import io.etherware.rt.platform.ThreadPolicy;
import io.etherware.rt.scheduling.ThreadSchedulingRule;
import java.net.InetSocketAddress;
import java.util.List;

/**
 * The bounds {@link NetworkConfig}'s constructor checks, by group of settings, in the order the
 * constructor calls them; each failure names the field, its value and the valid range or fix.
 *
 * <p>Stateless; called on the thread that builds the configuration, once per configuration.
 */
final class NetworkConfigChecks {

    private NetworkConfigChecks() {
    }

    /** The frame limit and the per-peer message queue and window. */
    static void frames(int maxFrameBytes, int queueCapacity, int windowMessages) {
        requireRange("maxFrameBytes", maxFrameBytes, NetworkConfig.MIN_FRAME_BYTES, 256 << 20);
        requireRange("queueCapacity", queueCapacity, 1, 10_000_000);
        requireRange("windowMessages", windowMessages, 4, 1 << 20);
    }

    /** A codec given, whose document limit becomes the frame limit a node says in its HELLO. */
    static void codec(MessageCodec codec) {
        if (codec != null && codec.maxDocumentBytes() < NetworkConfig.MIN_CODEC_DOCUMENT_BYTES) {
            throw new IllegalArgumentException("codec.maxDocumentBytes()=" + codec.maxDocumentBytes() + " must be at"
                    + " least " + NetworkConfig.MIN_CODEC_DOCUMENT_BYTES + ": a node tells its peers the largest"
                    + " message it takes, and peers refuse a node that takes less");
        }
    }

    /** The heartbeat, whose timeout must leave room for two intervals. */
    static void heartbeats(long heartbeatIntervalNs, long heartbeatTimeoutNs) {
        requirePositive("heartbeatIntervalNs", heartbeatIntervalNs);
        if (heartbeatTimeoutNs < 2 * heartbeatIntervalNs) {
            throw new IllegalArgumentException("heartbeatTimeoutNs=" + heartbeatTimeoutNs + " must be at least twice"
                    + " heartbeatIntervalNs=" + heartbeatIntervalNs + ", or a healthy idle peer looks dead");
        }
    }

    /** The handshake and dial timeouts, the redial backoff and the grace of a peer that is down. */
    static void dialing(long handshakeTimeoutNs, long connectTimeoutNs, long reconnectInitialBackoffNs,
                        long reconnectMaxBackoffNs, double reconnectJitter, long peerDownGraceNs) {
        requirePositive("handshakeTimeoutNs", handshakeTimeoutNs);
        requirePositive("connectTimeoutNs", connectTimeoutNs);
        requirePositive("reconnectInitialBackoffNs", reconnectInitialBackoffNs);
        if (reconnectMaxBackoffNs < reconnectInitialBackoffNs) {
            throw new IllegalArgumentException("reconnectMaxBackoffNs=" + reconnectMaxBackoffNs
                    + " must be at least reconnectInitialBackoffNs=" + reconnectInitialBackoffNs);
        }
        if (!(reconnectJitter >= 0 && reconnectJitter < 1)) {
            throw new IllegalArgumentException("reconnectJitter=" + reconnectJitter + " must be in [0, 1)");
        }
        requirePositive("peerDownGraceNs", peerDownGraceNs);
    }

    /** NetworkTime's exchanges with each peer. */
    static void timeProbes(long timeProbeIntervalNs, int timeProbeBurst, int timeWindowSize) {
        requirePositive("timeProbeIntervalNs", timeProbeIntervalNs);
        requireRange("timeProbeBurst", timeProbeBurst, 0, 64);
        requireRange("timeWindowSize", timeWindowSize, 1, 1024);
    }

    /** The bounds on connections and relays, and the byte bounds per peer (at least two frames). */
    static void limits(int maxConnections, int maxHops, int maxPendingHandshakes, int maxFrameBytes,
                       long maxQueuedBytesPerPeer, long maxInboundBytesPerPeer) {
        requireRange("maxConnections", maxConnections, 1, 100_000);
        requireRange("maxHops", maxHops, 0, 32);
        requireRange("maxPendingHandshakes", maxPendingHandshakes, 1, 100_000);
        requireRange("maxQueuedBytesPerPeer", maxQueuedBytesPerPeer, 2L * maxFrameBytes, 1L << 40);
        requireRange("maxInboundBytesPerPeer", maxInboundBytesPerPeer, 2L * maxFrameBytes, 1L << 40);
    }

    /** The reader and writer threads' real-time priorities (when given) and the lanes. */
    static void threads(ThreadPolicy threadPolicy, ThreadPolicy bulkThreadPolicy, int lanes) {
        requirePriority("threadPolicy", threadPolicy);
        requirePriority("bulkThreadPolicy", bulkThreadPolicy);
        requireRange("lanes", lanes, 1, 2);
    }

    /** For links that authenticate no one and were not chosen insecure: every address on loopback. */
    static void loopbackOnly(InetSocketAddress listenAddress, List<InetSocketAddress> peers) {
        requireLoopback("listenAddress", listenAddress);
        for (InetSocketAddress peer : peers) {
            requireLoopback("peer", peer);
        }
    }

    /** Whether the listen address or a peer is not a loopback address. */
    static boolean anyBeyondLoopback(InetSocketAddress listenAddress, List<InetSocketAddress> peers) {
        boolean beyond = !isLoopback(listenAddress);
        for (InetSocketAddress peer : peers) {
            beyond |= !isLoopback(peer);
        }
        return beyond;
    }

    private static boolean isLoopback(InetSocketAddress address) {
        return !address.isUnresolved() && address.getAddress().isLoopbackAddress();
    }

    private static void requireLoopback(String field, InetSocketAddress address) {
        if (!isLoopback(address)) {
            throw new IllegalArgumentException(field + "=" + address + " is beyond loopback, and plain TCP"
                    + " authenticates no one: configure TLS (connectionFactory(ConnectionFactory.tls(...))), or, on a"
                    + " network you trust, choose plain links with insecure(true)");
        }
    }

    private static void requireRange(String field, long value, long min, long max) {
        if (value < min || value > max) {
            throw new IllegalArgumentException(field + "=" + value + " must be in [" + min + ", " + max + "]");
        }
    }

    private static void requirePriority(String field, ThreadPolicy policy) {
        if (policy != null && policy.isRealtime() && (policy.priority() < ThreadSchedulingRule.MIN_REALTIME_PRIORITY
                || policy.priority() > ThreadSchedulingRule.MAX_REALTIME_PRIORITY)) {
            throw new IllegalArgumentException(field + ".priority=" + policy.priority() + " must be in "
                    + ThreadSchedulingRule.MIN_REALTIME_PRIORITY + ".." + ThreadSchedulingRule.MAX_REALTIME_PRIORITY);
        }
    }

    private static void requirePositive(String field, long valueNs) {
        if (valueNs <= 0) {
            throw new IllegalArgumentException(field + "=" + valueNs + " must be > 0");
        }
    }
}
