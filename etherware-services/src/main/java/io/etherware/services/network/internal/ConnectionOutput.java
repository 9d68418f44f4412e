package io.etherware.services.network.internal;

import java.io.IOException;
import java.util.ArrayList;
import java.util.List;

/**
 * The output side of one established {@link Connection}: writes the writer thread's turns and the
 * frames senders write directly, and keeps what the rest must know of it: when it last wrote,
 * whether a write is blocked, how much the peer may not have read yet, and the acknowledgement it
 * last carried.
 *
 * <p>Thread-safety: written only by whoever owns the connection's output (the writer thread, or a
 * sender writing directly; see {@link Link#enqueue}); its volatile state is read from any thread.
 */
final class ConnectionOutput {

    private final FrameWriter writer;
    private final NetworkContext context;
    private final Link link;
    private final String peerId;
    private final int peerMaxFrameBytes;
    /** Unacknowledged bytes below which a sender may write directly without ever blocking. */
    private final int directBudgetBytes;

    private volatile long lastWriteNs;
    /** When the writer thread's current write began, or 0. */
    private volatile long writingSinceNs;
    private volatile long lastAckSent;
    /** Bytes framed on this connection; written by whoever owns the output. */
    private volatile long bytesWritten;
    /** Where the last message frame written ends. */
    private volatile long lastDataEndOffset;
    /** Bytes the peer has certainly read: up to the last message frame, once all were acknowledged. */
    private volatile long readByPeerOffset;

    /**
     * @param writer            the connection's frame writer, past the handshake's frames
     * @param peerMaxFrameBytes the largest frame the peer takes (its HELLO, within this node's limit)
     * @param directBudgetBytes see {@link #fitsDirectWrite}
     */
    ConnectionOutput(FrameWriter writer, NetworkContext context, Link link, String peerId, int peerMaxFrameBytes,
                     int directBudgetBytes) {
        this.writer = writer;
        this.context = context;
        this.link = link;
        this.peerId = peerId;
        this.peerMaxFrameBytes = peerMaxFrameBytes;
        this.directBudgetBytes = directBudgetBytes;
        this.bytesWritten = writer.bytes();
        this.lastWriteNs = NetworkContext.nowNs();
    }

    /** Writes one turn of the writer thread of {@code connection}. */
    void write(Connection connection, WriterTurn turn) throws IOException {
        writingSinceNs = NetworkContext.nowNs();
        try {
            writeTurn(connection, turn);
        } finally {
            writingSinceNs = 0;
        }
    }

    /**
     * How long the current write has been blocked (0: none in progress): a peer that reads nothing
     * fills the socket's buffers, and the writer's next write never returns.
     */
    long writeBlockedForNs(long nowNs) {
        long since = writingSinceNs;
        return since == 0 ? 0 : nowNs - since;
    }

    private void writeTurn(Connection connection, WriterTurn turn) throws IOException {
        // The turn's new messages are numbered before anything is written: kept in flight from
        // here on, they are sent again on the next connection if a write below fails, instead of
        // being in neither the queue nor the stream.
        List<InFlight> fresh = turn.fresh.isEmpty() ? List.of() : assign(connection, turn.fresh);
        long ackNow = link.inboundCount();
        boolean carriedAck = false;
        if (turn.reject != null) {
            writer.reject(turn.reject.seq(), turn.reject.reason());
        }
        if (turn.announce != null) {
            writer.announce(turn.announce);
        }
        for (InFlight again : turn.resend) {
            writer.data(again.seq(), ackNow, again.outgoing().hops(), again.xml());
            context.counters().resent.increment();
            carriedAck = true;
        }
        if (carriedAck) {
            lastDataEndOffset = writer.bytes();
        }
        if (!fresh.isEmpty()) {
            for (InFlight entry : fresh) {
                writer.data(entry.seq(), ackNow, entry.outgoing().hops(), entry.xml());
            }
            lastDataEndOffset = writer.bytes();
            context.counters().sent.add(fresh.size());
            carriedAck = true;
        }
        if (turn.sync) {
            writer.sync(); // after the messages a NONE message of lane 1 waits for
        }
        if (turn.ack && !carriedAck) {
            writer.ack(ackNow);
            carriedAck = true;
        }
        if (carriedAck) {
            lastAckSent = ackNow;
        }
        if (turn.heartbeat) {
            writer.heartbeat();
        }
        if (turn.probe || !turn.timeReplies.isEmpty()) {
            // Time frames go out alone, stamped just before they leave: queued bytes ahead of
            // them would count as path delay.
            writer.flush();
            for (long[] request : turn.timeReplies) {
                writer.timeReply(request[0], request[1], context.kernel().clock().epochNanos());
                writer.flush();
            }
            if (turn.probe) {
                writer.timeRequest(context.kernel().clock().epochNanos());
            }
        }
        if (turn.bye != null) {
            writer.bye(turn.bye.code(), turn.bye.text());
        }
        writer.flush();
        bytesWritten = writer.bytes();
        lastWriteNs = NetworkContext.nowNs();
    }

    /**
     * Numbers a turn's new messages (encoded by their senders) and keeps them in flight; reports
     * those that cannot go. Empty if the connection is no longer its lane's (they went back to the
     * queue).
     */
    private List<InFlight> assign(Connection connection, List<Outgoing> taken) {
        var encoded = new ArrayList<Outgoing>(taken.size());
        var tooLarge = new ArrayList<Outgoing>();
        for (Outgoing outgoing : taken) {
            if (outgoing.xml().length + Frame.DATA_OVERHEAD_BYTES <= peerMaxFrameBytes) {
                encoded.add(outgoing);
            } else {
                tooLarge.add(outgoing); // queued before this peer said its limit, below this node's own
            }
        }
        List<InFlight> assigned = link.assign(connection, encoded, tooLarge);
        for (Outgoing outgoing : tooLarge) {
            context.losses().lost(outgoing.message(), "its frame of " + (outgoing.xml().length
                    + Frame.DATA_OVERHEAD_BYTES) + " bytes is over the " + peerMaxFrameBytes + " bytes node '" + peerId
                    + "' accepts");
        }
        return assigned == null ? List.of() : assigned;
    }

    /**
     * Writes one message frame on the calling thread, which owns the output meanwhile (see
     * {@link Link#enqueue}).
     */
    void writeDirect(InFlight entry) throws IOException {
        long ackNow = link.inboundCount();
        writer.data(entry.seq(), ackNow, entry.outgoing().hops(), entry.xml());
        writer.flush();
        lastDataEndOffset = writer.bytes();
        bytesWritten = lastDataEndOffset;
        lastAckSent = ackNow;
        lastWriteNs = NetworkContext.nowNs();
        context.counters().sent.increment();
    }

    int peerMaxFrameBytes() {
        return peerMaxFrameBytes;
    }

    /**
     * Whether a sender may write {@code frameBytes} more directly: the bytes the peer may not have
     * read yet (everything after the last message frame it acknowledged, control frames included)
     * plus these stay within a quarter of the socket's send buffer, so the write cannot block
     * even on a peer that stopped reading.
     */
    boolean fitsDirectWrite(int frameBytes) {
        return bytesWritten - readByPeerOffset + frameBytes <= directBudgetBytes;
    }

    /**
     * Every message frame written so far is acknowledged (link's lock held): the peer has read
     * the stream up to the last of them. A frame still being written ends later, so this errs
     * on the safe side.
     */
    void allDataAcknowledged() {
        readByPeerOffset = Math.max(readByPeerOffset, lastDataEndOffset);
    }

    long heartbeatDueNs() {
        return lastWriteNs + context.config().heartbeatIntervalNs();
    }

    /** The acknowledgement (messages of the peer's stream) the last frame carrying one said. */
    long lastAckSent() {
        return lastAckSent;
    }

    /** Whether acknowledgements are owed: messages delivered since the last one sent. */
    boolean owesAck() {
        return link.inboundCount() > lastAckSent;
    }
}
