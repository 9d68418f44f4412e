package io.etherware.services.network;

/**
 * Why a connection between two nodes ended. The reasons marked bad input are a peer (or
 * something posing as one) breaking the protocol: the connection is closed, the reason logged
 * and counted, and the node and its other connections carry on.
 *
 * <p>Each reason has a fixed code on the wire (the BYE frame of {@code NETWORK-PROTOCOL.md}).
 * Immutable.
 */
public enum CloseReason {
    /** This node's messenger is closing. */
    SHUTDOWN(1, false),
    /** The peer closed the connection (end of stream, or its BYE). */
    PEER_CLOSED(2, false),
    /** Another connection to the same peer is kept (one connection per lane per pair of nodes). */
    DUPLICATE(3, false),
    /** Nothing arrived from the peer within the heartbeat timeout. */
    HEARTBEAT_TIMEOUT(4, false),
    /** A socket error: reset, unreachable, refused while writing. */
    IO_ERROR(5, false),
    /** The peer did not complete the handshake in time. */
    HANDSHAKE_TIMEOUT(6, true),
    /** The first bytes were not an Etherware handshake, or it named an impossible node. */
    BAD_HANDSHAKE(7, true),
    /** The peer speaks another protocol version. */
    PROTOCOL_VERSION(8, true),
    /** A frame longer than the frame limit. */
    OVERSIZE_FRAME(9, true),
    /** A frame of an unknown type, or one whose body does not parse. */
    MALFORMED_FRAME(10, true),
    /** A message frame whose XML does not decode ({@link io.etherware.core.codec.MessageCodec}). */
    MALFORMED_MESSAGE(11, true),
    /** A message frame out of sequence (a gap, or an acknowledgement of what was never sent). */
    SEQUENCE_ERROR(12, true),
    /**
     * The peer could not be authenticated: its TLS handshake failed, or its HELLO names another
     * node than its certificate.
     */
    AUTHENTICATION_FAILED(13, true),
    /** A message sent directly whose id names another node than the connection's. */
    ORIGIN_MISMATCH(14, true),
    /** The peer read nothing of what was written to it within the heartbeat timeout. */
    NOT_READING(15, false),
    /** A flood of new connections pushed this one, still in its handshake, out. */
    HANDSHAKE_EVICTED(16, false);

    private final int code;
    private final boolean badInput;

    CloseReason(int code, boolean badInput) {
        this.code = code;
        this.badInput = badInput;
    }

    /**
     * The reason's code on the wire.
     *
     * @return the code, 1 to 16, fixed per reason
     */
    public int code() {
        return code;
    }

    /**
     * Whether the peer broke the protocol (counted as bad input).
     *
     * @return true for the bad-input reasons
     */
    public boolean isBadInput() {
        return badInput;
    }

    /**
     * The reason for a wire code.
     *
     * @param code a code from a BYE frame
     * @return its reason, or {@link #PEER_CLOSED} for a code this version does not know
     */
    public static CloseReason ofCode(int code) {
        for (CloseReason reason : values()) {
            if (reason.code == code) {
                return reason;
            }
        }
        return PEER_CLOSED;
    }
}
