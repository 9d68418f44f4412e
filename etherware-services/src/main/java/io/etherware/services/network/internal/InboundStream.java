package io.etherware.services.network.internal;

import io.etherware.services.network.CloseReason;

/**
 * A peer's stream of messages on one lane as this node receives it: which stream it is, and how
 * many of its messages this node's kernel has (what this node acknowledges). A message is handed
 * over only in its place in the stream and only once.
 *
 * <p>Locking: callers hold this object's monitor around {@link #resume} and {@link #deliver}
 * (the {@link Link} does, so that two connections during a replacement never deliver out of
 * order or twice); {@link #count} is read without it.
 */
final class InboundStream {

    // Guarded by this.
    private long streamId;
    /** Written under this object's monitor; read without it by writers (piggybacked acks). */
    private volatile long count;

    /** The hand-over of one inbound message to the kernel. */
    @FunctionalInterface
    interface Delivery {
        void deliver() throws ProtocolException;
    }

    long streamId() {
        return streamId;
    }

    /** Messages of the stream handed to this node's kernel. */
    long count() {
        return count;
    }

    /** The peer sends on {@code peerStreamId} from now on: another stream than ours starts from 0. */
    void resume(long peerStreamId) {
        if (peerStreamId != streamId) {
            streamId = peerStreamId;
            count = 0;
        }
    }

    /**
     * Runs {@code delivery} if message {@code seq} is the next of the stream, and counts it
     * (delivered or refused for good, it is never asked for again).
     *
     * @return false for a duplicate, which is dropped
     * @throws ProtocolException SEQUENCE_ERROR for a message beyond the next, or what the delivery threw
     */
    boolean deliver(long seq, Delivery delivery) throws ProtocolException {
        if (seq < count) {
            return false;
        }
        if (seq > count) {
            throw new ProtocolException(CloseReason.SEQUENCE_ERROR, "message frame " + seq + " where " + count
                    + " was expected");
        }
        try {
            delivery.deliver();
        } finally {
            count = seq + 1;
        }
        return true;
    }
}
