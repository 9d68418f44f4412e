package io.etherware.services.network.internal;

import java.util.concurrent.TimeUnit;

/**
 * Whether a lane to a peer takes messages, across connections (NETWORK-PROTOCOL.md, "Liveness"):
 * since when no connection carries it, whether it was given up after the grace period (alone,
 * until it connects again, or retired with its peer for good), and whether the messenger closed.
 *
 * <p>Locking: guarded by its link's lock; every method is called with it held, except
 * {@link #downSinceNs}, a volatile read. Takes no lock.
 */
final class LaneLife {

    private final String nodeId;
    private final NetworkContext context;
    private volatile long downSinceNs = NetworkContext.nowNs();
    private boolean expired;
    /** Expired and removed from the messenger's peers: a later connection gets a new Peer. */
    private boolean retired;
    private boolean closed;

    /** @param nodeId the peer the lane leads to */
    LaneLife(String nodeId, NetworkContext context) {
        this.nodeId = nodeId;
        this.context = context;
    }

    /** Refuses a message, by throwing, if the messenger is closed or the lane was given up. */
    void checkTakesMessages() {
        if (closed) {
            throw new IllegalStateException("the network messenger of node '" + context.nodeId() + "' is closed");
        }
        if (expired) {
            throw new IllegalStateException("node '" + nodeId + "' is unreachable: disconnected for more than "
                    + TimeUnit.NANOSECONDS.toMillis(context.config().peerDownGraceNs()) + " ms");
        }
    }

    /** Whether a connection may carry the lane: neither closed nor retired. */
    boolean mayConnect() {
        return !(closed || retired);
    }

    /** A connection carries the lane: it takes messages again. */
    void connected() {
        expired = false;
    }

    /** No connection carries the lane from now on. */
    void down() {
        downSinceNs = NetworkContext.nowNs();
    }

    /** Since when no connection carries the lane (meaningful while none does). Lock-free. */
    long downSinceNs() {
        return downSinceNs;
    }

    /** Retires the lane with its peer, for good; false if it is already retired or closed. */
    boolean retire() {
        if (retired || closed) {
            return false;
        }
        expired = true; // perhaps already, alone: what was put back since is given up now
        retired = true;
        return true;
    }

    /**
     * Gives the lane up alone if it has been down the grace period by {@code nowNs}; false if it is
     * closed, not down that long, or already given up with {@code nothingWaits} since.
     */
    boolean expireAlone(long nowNs, boolean nothingWaits) {
        if (closed || nowNs - downSinceNs < context.config().peerDownGraceNs() || expired && nothingWaits) {
            return false; // (messages a replaced writer put back after it expired are given up too)
        }
        expired = true;
        return true;
    }

    /** The messenger closes: the lane refuses messages from now on. */
    void close() {
        closed = true;
    }
}
