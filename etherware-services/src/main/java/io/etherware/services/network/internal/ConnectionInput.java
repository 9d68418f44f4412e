package io.etherware.services.network.internal;

import io.etherware.core.kernel.OrderMarker;
import io.etherware.core.message.Message;
import io.etherware.core.message.MessageFormatException;
import io.etherware.core.message.Origin;
import io.etherware.services.network.CloseReason;
import io.etherware.services.time.TimeSample;
import java.io.EOFException;
import java.io.IOException;
import java.net.SocketTimeoutException;
import java.util.concurrent.TimeUnit;

/**
 * The input side of one established {@link Connection}: the reader's loop after the handshake.
 * It hands the peer's messages to the kernel in stream order, with the origin this connection
 * vouches for, and stops reading while the peer's messages held here are at their bound; it
 * answers control frames through the connection's writer requests, and closes the connection
 * with the reason the stream ended for.
 *
 * <p>Thread-safety: the connection's reader thread only (the thread that ran the handshake),
 * which owns its state.
 */
final class ConnectionInput {

    private static final org.slf4j.Logger log =
            org.slf4j.LoggerFactory.getLogger("io.etherware.services.network.NetworkMessenger");

    /** A receiver acknowledges at least every this many bytes of messages. */
    static final int ACK_EVERY_BYTES = 64 * 1024;

    private final Connection connection;
    private final NetworkContext context;
    private final ConnectionEvents events;
    private final FrameReader reader;
    private final Peer peer;
    private final Link link;
    private final int lane;
    /** The peer's incarnation, from its HELLO. */
    private final long peerIncarnation;
    /** Whether the connection authenticated the peer (TLS). */
    private final boolean authenticated;
    private final ConnectionOutput output;

    /** Message bytes received since the last acknowledgement was asked for. */
    private long bytesSinceAckRequest;

    /**
     * @param connection the connection, past its handshake, whose link and streams these frames
     *                   belong to
     * @param reader     its frame reader, past the handshake's frames
     */
    ConnectionInput(Connection connection, NetworkContext context, ConnectionEvents events, FrameReader reader,
                    Peer peer, Link link, int lane, long peerIncarnation, boolean authenticated,
                    ConnectionOutput output) {
        this.connection = connection;
        this.context = context;
        this.events = events;
        this.reader = reader;
        this.peer = peer;
        this.link = link;
        this.lane = lane;
        this.peerIncarnation = peerIncarnation;
        this.authenticated = authenticated;
        this.output = output;
    }

    /** Reads and handles frames until the connection closes, then closes it for what ended it. */
    void readLoop() {
        context.lanes().get(lane).configureCurrent();
        try {
            while (!connection.isClosing()) {
                switch (reader.next()) {
                    case Frame.Data data -> onData(data);
                    case Frame.Ack ack -> link.onAck(connection, ack.count());
                    case Frame.Heartbeat heartbeat -> { }
                    case Frame.Sync sync -> connection.requestAck(); // every DATA before it is delivered
                    case Frame.Announce announced -> {
                        if (link.active() == connection) {
                            events.announced(peer, peerIncarnation, announced);
                        }
                    }
                    case Frame.TimeRequest request -> connection.requestTimeReply(request.t1(),
                            context.kernel().clock().epochNanos());
                    case Frame.TimeReply reply -> context.networkTime().onExchange(peer.nodeId,
                            new TimeSample(reply.t1(), reply.t2(), reply.t3(), context.kernel().clock().epochNanos()));
                    case Frame.Reject rejected -> {
                        Outgoing refused = link.onReject(connection, rejected.seq());
                        if (refused != null) {
                            context.losses().lost(refused.message(), "node '" + peer.nodeId + "' refused it: " + rejected.reason());
                        }
                    }
                    case Frame.Bye goodbye -> {
                        connection.goodbyeRead();
                        if (CloseReason.ofCode(goodbye.code()) == CloseReason.SHUTDOWN && link.active() == connection) {
                            events.peerShutDown(peer);
                        }
                        connection.close(CloseReason.PEER_CLOSED, "node '" + peer.nodeId + "' closed the connection: "
                                + CloseReason.ofCode(goodbye.code()) + ": " + goodbye.text());
                        return;
                    }
                    case Frame.Hello unexpected -> throw new ProtocolException(CloseReason.MALFORMED_FRAME, "HELLO again");
                    case Frame.Resume unexpected -> throw new ProtocolException(CloseReason.MALFORMED_FRAME,
                            "RESUME after the handshake");
                }
            }
        } catch (RefusedMessageException e) {
            connection.requestReject(new Frame.Reject(e.seq, e.getMessage()));
            connection.close(e.reason(), e.getMessage());
        } catch (ProtocolException e) {
            connection.close(e.reason(), e.getMessage());
            if (e instanceof StreamResetException reset) {
                context.losses().reportLost(reset.lost, "the streams with node '" + peer.nodeId
                        + "' disagreed; its fate is unknown");
            }
        } catch (SocketTimeoutException e) {
            connection.close(CloseReason.HEARTBEAT_TIMEOUT, "nothing from node '" + peer.nodeId + "' for "
                    + TimeUnit.NANOSECONDS.toMillis(context.config().heartbeatTimeoutNs()) + " ms");
        } catch (EOFException e) {
            connection.close(CloseReason.PEER_CLOSED, "node '" + peer.nodeId + "' closed the connection");
        } catch (IOException e) {
            connection.close(connection.isClosing() ? CloseReason.SHUTDOWN : CloseReason.IO_ERROR,
                    "reading from node '" + peer.nodeId + "' failed: " + e);
        }
    }

    /**
     * A message frame refused for good (its XML does not decode, or it lies about its origin): its
     * sender hears of it by REJECT, and the connection closes.
     */
    private static final class RefusedMessageException extends ProtocolException {
        final long seq;

        RefusedMessageException(long seq, CloseReason reason, String text, Throwable cause) {
            super(reason, "message frame " + seq + " " + text, cause);
            this.seq = seq;
        }
    }

    private void onData(Frame.Data data) throws ProtocolException {
        link.onAck(connection, data.ack());
        awaitInboundRoom(data.xml().length);
        boolean delivered = link.deliverInOrder(connection, data.seq(), () -> {
            Message message;
            try {
                message = context.codec().decode(data.xml());
            } catch (MessageFormatException e) {
                throw new RefusedMessageException(data.seq(), CloseReason.MALFORMED_MESSAGE, "does not decode: "
                        + e.getMessage(), e);
            }
            deliverLocally(context.networkTime().toLocal(peer.nodeId, message.withOrigin(originOf(data, message))));
        });
        if (!delivered) {
            if (link.active() != connection) {
                return; // replaced: the new connection carries the stream on, and closes this one
            }
            context.counters().duplicates.increment();
        } else {
            bytesSinceAckRequest += data.xml().length;
            if (link.inboundCount() - output.lastAckSent() >= context.config().windowMessages() / 4
                    || bytesSinceAckRequest >= ACK_EVERY_BYTES) {
                // By count for small messages, by bytes for large ones: a sender keeps at most
                // OutboundStream.LOW_IN_FLIGHT_BYTES of LOW messages (one lane) unacknowledged.
                bytesSinceAckRequest = 0;
                connection.requestAck();
            }
        }
    }

    /**
     * Where a message came from, from this connection's node, never from the message alone: sent
     * directly (hops 0), its id must name this connection's node; relayed, the relay vouches for
     * the origin its id names (the rule is in {@link Origin}).
     */
    private Origin originOf(Frame.Data data, Message message) throws RefusedMessageException {
        String named = message.messageId().nodeId();
        if (data.hops() == 0) {
            if (!named.equals(peer.nodeId)) {
                throw new RefusedMessageException(data.seq(), CloseReason.ORIGIN_MISMATCH, "has id " + message.messageId()
                        + " of node '" + named + "' but was sent directly by node '" + peer.nodeId
                        + "': a node may only send messages under its own id", null);
            }
            return new Origin(peer.nodeId, peer.nodeId, 0, authenticated, data.xml().length);
        }
        return new Origin(named, peer.nodeId, data.hops(), authenticated, data.xml().length);
    }

    /**
     * Waits, not reading, while this peer's messages held in the kernel's queues and this one
     * would exceed {@link io.etherware.services.network.NetworkConfig#maxInboundBytesPerPeer} (half
     * of it on lane 1, so LOW messages never take the room of HIGH ones): the peer's writes then
     * back up over TCP, and a peer that floods a slow component is slowed down instead of filling
     * the heap. Polls every millisecond; ends when the connection closes.
     */
    private void awaitInboundRoom(int bytes) {
        long max = context.config().maxInboundBytesPerPeer() / (lane == 0 ? 1 : 2);
        if (context.kernel().queuedBytesFrom(peer.nodeId) + bytes <= max) {
            return;
        }
        context.counters().inboundPauses.increment();
        while (!connection.isClosing() && context.kernel().queuedBytesFrom(peer.nodeId) + bytes > max) {
            java.util.concurrent.locks.LockSupport.parkNanos(1_000_000);
        }
    }

    /** Hands a message from the peer, its origin set, to the kernel. */
    private void deliverLocally(Message message) {
        if (message.contents() instanceof OrderMarker marker && message.profile().equals(context.kernel().profile())) {
            context.flushes().answered(marker.token()); // the answer to a marker of this node's
            return;
        }
        try {
            context.kernel().send(message);
            context.counters().received.increment();
        } catch (RuntimeException e) {
            context.counters().undeliverable.increment();
            log.warn("node {}: the kernel refused message {} to '{}' from the network: {}", context.nodeId(),
                    message.messageId(), message.profile(), e.toString());
        }
    }
}
