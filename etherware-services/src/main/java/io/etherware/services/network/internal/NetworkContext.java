package io.etherware.services.network.internal;

import io.etherware.core.kernel.Kernel;
import io.etherware.services.network.CloseReason;
import io.etherware.services.network.NetworkConfig;
import io.etherware.services.time.NetworkTime;
import java.util.List;
import java.util.concurrent.Executor;
import java.util.concurrent.RejectedExecutionException;
import java.util.concurrent.ThreadLocalRandom;

/**
 * What the messenger's parts share, made once when it starts and handed to each {@link Link} and
 * {@link Connection}: they get what they need from here rather than from the {@link Engine}.
 * Immutable; its parts are thread-safe.
 *
 * @param nodeId      this node's id
 * @param incarnation this messenger's random non-zero incarnation (HELLO)
 * @param kernel      where messages from the network go
 * @param config      the messenger's configuration
 * @param counters    the messenger's counters
 * @param networkTime the clock offsets to the peers
 * @param losses      what happens to messages that cannot be delivered
 * @param lanes       each lane's thread policy and CPUs, by lane
 * @param control     the control thread, for work a caller must not wait for
 * @param codec       encodes and decodes the messages ({@link NetworkConfig#codecFor})
 * @param flushes     the markers that keep a sender's order when a profile moves ({@link SenderOrder})
 */
record NetworkContext(String nodeId, long incarnation, Kernel kernel, NetworkConfig config, Counters counters,
                      NetworkTime networkTime, Losses losses, List<IoThreads> lanes, Executor control,
                      io.etherware.core.codec.MessageCodec codec, RouteFlushes flushes) {

    NetworkContext {
        lanes = List.copyOf(lanes);
    }

    /** The lane that carries a message of {@code criticality}: HIGH and MIDDLE on 0, LOW and NONE on 1. */
    int laneOf(io.etherware.core.message.Criticality criticality) {
        return laneOf(lanes.size(), criticality);
    }

    /** {@link #laneOf(io.etherware.core.message.Criticality)} for a messenger of {@code laneCount} lanes. */
    static int laneOf(int laneCount, io.etherware.core.message.Criticality criticality) {
        return laneCount == 1 || criticality.compareTo(io.etherware.core.message.Criticality.MIDDLE) >= 0 ? 0 : 1;
    }

    /**
     * The largest frame this node takes from a peer, said in its HELLO: {@code maxFrameBytes}, or
     * less when the codec's document limit is lower, so that a peer never sends a message this
     * node's codec would refuse (and close the connection over): it refuses it itself, to its
     * sender, and the connection carries on.
     */
    int acceptedFrameBytes() {
        return (int) Math.min(config.maxFrameBytes(), (long) codec.maxDocumentBytes() + Frame.DATA_OVERHEAD_BYTES);
    }

    /** Closes a connection off the calling thread (a sender must not wait for the close). */
    void closeLater(Connection connection, CloseReason reason, String detail) {
        try {
            control.execute(() -> connection.close(reason, detail));
        } catch (RejectedExecutionException e) {
            // The messenger is closing and closes every connection itself.
        }
    }

    static long nowNs() {
        return System.nanoTime();
    }

    /** A random non-zero stream id. */
    static long newStreamId() {
        return nonZero(ThreadLocalRandom.current().nextLong());
    }

    static long nonZero(long value) {
        return value == 0 ? 1 : value;
    }
}
