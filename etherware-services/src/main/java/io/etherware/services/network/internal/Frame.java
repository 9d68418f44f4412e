package io.etherware.services.network.internal;

import io.etherware.core.message.Profile;
import java.util.List;

/**
 * The frames of the node-to-node protocol, version {@value #VERSION} ({@code NETWORK-PROTOCOL.md}): each is
 * a 4-byte big-endian length, a type byte and a body.
 *
 * <p>Immutable values.
 */
sealed interface Frame {

    int MAGIC = 0x45575254; // "EWRT"
    int VERSION = 3;
    /** Most lanes (connections per pair of nodes) a HELLO may state. */
    int MAX_LANES = 8;

    byte HELLO = 1;
    byte RESUME = 2;
    byte DATA = 3;
    byte ACK = 4;
    byte HEARTBEAT = 5;
    byte ANNOUNCE = 6;
    byte TIME_REQUEST = 7;
    byte TIME_REPLY = 8;
    byte REJECT = 9;
    byte BYE = 10;
    byte SYNC = 11;

    /** Largest HELLO or RESUME: a peer that sends more before the handshake is not a peer. */
    int MAX_HANDSHAKE_FRAME_BYTES = 1024;
    /**
     * Smallest HELLO: type, magic, version, a node id of one byte (with its length), incarnation,
     * clock, maxFrameBytes, lanes, lane.
     */
    int MIN_HELLO_FRAME_BYTES = 1 + 4 + 2 + 2 + 1 + 8 + 8 + 4 + 1 + 1;
    /** Type byte plus DATA's seq, ack and hops. */
    int DATA_OVERHEAD_BYTES = 1 + 8 + 8 + 1;

    /**
     * Identity: first frame each way.
     *
     * @param lanes how many connections per pair of nodes the sender runs (both must agree)
     * @param lane  from the dialing side, the lane this connection carries (0: HIGH and MIDDLE
     *              messages, 1: LOW and NONE); the accepting side writes 0 and is not read
     */
    record Hello(int version, String nodeId, long incarnation, long epochNs, int maxFrameBytes, int lanes, int lane)
            implements Frame {
    }

    /**
     * Where the streams stand: second frame each way.
     *
     * @param streamId      the stream this node sends on to the peer
     * @param knownStreamId the peer's stream this node last received from (0: none)
     * @param receivedCount messages of that stream handed to this node's kernel
     */
    record Resume(long streamId, long knownStreamId, long receivedCount) implements Frame {
    }

    /** One message: its sequence in the stream, the sender's acknowledgement, hops so far, XML. */
    record Data(long seq, long ack, int hops, byte[] xml) implements Frame {
    }

    /** Messages of the peer's stream handed to this node's kernel so far. */
    record Ack(long count) implements Frame {
    }

    enum Heartbeat implements Frame { INSTANCE }

    /** Acknowledge at once everything received so far (a NONE message of the other lane waits for it). */
    enum Sync implements Frame { INSTANCE }

    /** The full set of profiles the sender hosts, replacing any earlier announce. */
    record Announce(long version, List<Profile> profiles) implements Frame {
    }

    record TimeRequest(long t1) implements Frame {
    }

    record TimeReply(long t1, long t2, long t3) implements Frame {
    }

    /** The message {@code seq} was refused (did not decode); the connection closes after it. */
    record Reject(long seq, String reason) implements Frame {
    }

    /** The sender closes the connection, and why. */
    record Bye(int code, String text) implements Frame {
    }
}
