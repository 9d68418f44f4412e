package io.etherware.services.network.internal;

import io.etherware.core.message.MessageFormatException;
import io.etherware.core.message.Profile;
import io.etherware.services.network.CloseReason;
import java.io.BufferedInputStream;
import java.io.DataInputStream;
import java.io.EOFException;
import java.io.IOException;
import java.io.InputStream;
import java.nio.BufferUnderflowException;
import java.nio.ByteBuffer;
import java.nio.charset.CharacterCodingException;
import java.nio.charset.CodingErrorAction;
import java.nio.charset.StandardCharsets;
import java.util.ArrayList;
import java.util.HexFormat;
import java.util.List;

/**
 * Reads frames from one connection, checking every length and field before trusting it: a
 * violation is a {@link ProtocolException} naming what was wrong.
 *
 * <p>Not thread-safe: the connection's reader thread owns it.
 */
final class FrameReader {

    private static final int BUFFER_BYTES = 64 * 1024;

    private final DataInputStream in;
    private final int maxFrameBytes;

    FrameReader(InputStream input, int maxFrameBytes) {
        this.in = new DataInputStream(new BufferedInputStream(input, BUFFER_BYTES));
        this.maxFrameBytes = maxFrameBytes;
    }

    /**
     * The first frame of a connection, which must be a HELLO of this protocol. Garbage fails here:
     * an HTTP request, a port scanner's probe, random bytes.
     */
    Frame.Hello readHello() throws IOException {
        // Each part is checked as soon as it arrives: a first frame that cannot be a HELLO is
        // refused at once, not when the handshake times out.
        byte[] head = new byte[5];
        in.readFully(head, 0, 4);
        int length = ByteBuffer.wrap(head).getInt();
        if (length < Frame.MIN_HELLO_FRAME_BYTES || length > Frame.MAX_HANDSHAKE_FRAME_BYTES) {
            throw new ProtocolException(CloseReason.BAD_HANDSHAKE, "not an Etherware peer: the first bytes are "
                    + HexFormat.ofDelimiter(" ").formatHex(head, 0, 4) + ", not the length of a HELLO frame ("
                    + Frame.MIN_HELLO_FRAME_BYTES + " to " + Frame.MAX_HANDSHAKE_FRAME_BYTES + " bytes)");
        }
        head[4] = in.readByte();
        if (head[4] != Frame.HELLO) {
            throw new ProtocolException(CloseReason.BAD_HANDSHAKE, "not an Etherware peer: the first bytes are "
                    + HexFormat.ofDelimiter(" ").formatHex(head) + ", not a HELLO frame");
        }
        ByteBuffer body = body(length - 1);
        try {
            return hello(body);
        } catch (BufferUnderflowException e) {
            throw new ProtocolException(CloseReason.BAD_HANDSHAKE, "not an Etherware peer: HELLO frame of " + length
                    + " bytes is too short for its fields", e);
        }
    }

    private static Frame.Hello hello(ByteBuffer body) throws ProtocolException {
        int magic = body.getInt();
        if (magic != Frame.MAGIC) {
            throw new ProtocolException(CloseReason.BAD_HANDSHAKE, "not an Etherware peer: magic 0x"
                    + Integer.toHexString(magic) + " instead of 0x" + Integer.toHexString(Frame.MAGIC));
        }
        int version = Short.toUnsignedInt(body.getShort());
        if (version != Frame.VERSION) {
            throw new ProtocolException(CloseReason.PROTOCOL_VERSION, "the peer speaks protocol version " + version
                    + "; this node speaks version " + Frame.VERSION);
        }
        String nodeId = string(body, "nodeId");
        if (!Profile.isName(nodeId)) {
            throw new ProtocolException(CloseReason.BAD_HANDSHAKE, "the peer's node id '" + nodeId
                    + "' does not match " + Profile.NAME_PATTERN);
        }
        long incarnation = body.getLong();
        long epochNs = body.getLong();
        int peerMaxFrameBytes = body.getInt();
        if (peerMaxFrameBytes < Frame.MAX_HANDSHAKE_FRAME_BYTES) {
            throw new ProtocolException(CloseReason.BAD_HANDSHAKE, "the peer's maxFrameBytes=" + peerMaxFrameBytes
                    + " is below " + Frame.MAX_HANDSHAKE_FRAME_BYTES);
        }
        int lanes = Byte.toUnsignedInt(body.get());
        int lane = Byte.toUnsignedInt(body.get());
        if (lanes < 1 || lanes > Frame.MAX_LANES || lane >= lanes) {
            throw new ProtocolException(CloseReason.BAD_HANDSHAKE, "the peer's HELLO states lane " + lane + " of "
                    + lanes + " lanes: lanes must be in 1.." + Frame.MAX_LANES + " and the lane below them");
        }
        requireEnd(body, "HELLO");
        return new Frame.Hello(version, nodeId, incarnation, epochNs, peerMaxFrameBytes, lanes, lane);
    }

    /**
     * The next frame.
     *
     * @throws ProtocolException for an oversize, unknown or malformed frame
     * @throws EOFException      if the peer closed the stream (also in the middle of a frame)
     */
    Frame next() throws IOException {
        int length = in.readInt();
        if (length < 1) {
            throw new ProtocolException(CloseReason.MALFORMED_FRAME, "frame length " + length + " is below 1");
        }
        if (length > maxFrameBytes) {
            throw new ProtocolException(CloseReason.OVERSIZE_FRAME, "frame of " + length
                    + " bytes is over maxFrameBytes=" + maxFrameBytes);
        }
        byte type = in.readByte();
        int bodyBytes = length - 1;
        try {
            return switch (type) {
                case Frame.DATA -> readData(bodyBytes);
                case Frame.ACK -> new Frame.Ack(count(exactly(bodyBytes, 8, "ACK").getLong(), "ACK count"));
                case Frame.HEARTBEAT -> {
                    exactly(bodyBytes, 0, "HEARTBEAT");
                    yield Frame.Heartbeat.INSTANCE;
                }
                case Frame.SYNC -> {
                    exactly(bodyBytes, 0, "SYNC");
                    yield Frame.Sync.INSTANCE;
                }
                case Frame.TIME_REQUEST -> new Frame.TimeRequest(exactly(bodyBytes, 8, "TIME_REQUEST").getLong());
                case Frame.TIME_REPLY -> {
                    ByteBuffer body = exactly(bodyBytes, 24, "TIME_REPLY");
                    yield new Frame.TimeReply(body.getLong(), body.getLong(), body.getLong());
                }
                case Frame.RESUME -> {
                    ByteBuffer body = exactly(bodyBytes, 24, "RESUME");
                    long streamId = body.getLong();
                    if (streamId == 0) {
                        throw new ProtocolException(CloseReason.MALFORMED_FRAME, "RESUME streamId 0: a stream id is"
                                + " never 0 (0 means none, in knownStreamId only)");
                    }
                    yield new Frame.Resume(streamId, body.getLong(), count(body.getLong(), "RESUME receivedCount"));
                }
                case Frame.ANNOUNCE -> readAnnounce(body(bodyBytes));
                case Frame.REJECT -> {
                    ByteBuffer body = body(bodyBytes);
                    long seq = body.getLong();
                    String reason = string(body, "reason");
                    requireEnd(body, "REJECT");
                    yield new Frame.Reject(seq, reason);
                }
                case Frame.BYE -> {
                    ByteBuffer body = body(bodyBytes);
                    int code = Byte.toUnsignedInt(body.get());
                    String text = string(body, "text");
                    requireEnd(body, "BYE");
                    yield new Frame.Bye(code, text);
                }
                case Frame.HELLO -> throw new ProtocolException(CloseReason.MALFORMED_FRAME,
                        "a second HELLO on an established connection");
                default -> throw new ProtocolException(CloseReason.MALFORMED_FRAME, "unknown frame type " + type
                        + " (" + length + " bytes)");
            };
        } catch (java.nio.BufferUnderflowException e) {
            throw new ProtocolException(CloseReason.MALFORMED_FRAME, "frame type " + type + " of " + length
                    + " bytes is too short for its fields", e);
        }
    }

    private Frame.Data readData(int bodyBytes) throws IOException {
        if (bodyBytes < Frame.DATA_OVERHEAD_BYTES - 1) {
            throw new ProtocolException(CloseReason.MALFORMED_FRAME, "DATA frame of " + (bodyBytes + 1)
                    + " bytes is shorter than its header");
        }
        long seq = count(in.readLong(), "DATA seq");
        long ack = count(in.readLong(), "DATA ack");
        int hops = in.readUnsignedByte();
        byte[] xml = new byte[bodyBytes - (Frame.DATA_OVERHEAD_BYTES - 1)];
        in.readFully(xml);
        return new Frame.Data(seq, ack, hops, xml);
    }

    /** A sequence number or count: never negative. */
    private static long count(long value, String field) throws ProtocolException {
        if (value < 0) {
            throw new ProtocolException(CloseReason.MALFORMED_FRAME, field + " " + value + " is negative");
        }
        return value;
    }

    private static Frame.Announce readAnnounce(ByteBuffer body) throws ProtocolException {
        long version = body.getLong();
        int count = body.getInt();
        // Each profile takes at least 3 bytes (length and one character): bounds the list.
        if (count < 0 || count > body.remaining() / 3) {
            throw new ProtocolException(CloseReason.MALFORMED_FRAME, "ANNOUNCE claims " + count
                    + " profiles in " + body.remaining() + " bytes");
        }
        var profiles = new ArrayList<Profile>(count);
        for (int i = 0; i < count; i++) {
            String text = string(body, "profiles[" + i + "]");
            try {
                profiles.add(Profile.parse(text));
            } catch (MessageFormatException | IllegalArgumentException e) {
                throw new ProtocolException(CloseReason.MALFORMED_FRAME, "ANNOUNCE profiles[" + i + "] '" + text
                        + "' is not a profile: " + e.getMessage(), e);
            }
        }
        requireEnd(body, "ANNOUNCE");
        return new Frame.Announce(version, List.copyOf(profiles));
    }

    private ByteBuffer body(int bodyBytes) throws IOException {
        byte[] body = new byte[bodyBytes];
        in.readFully(body);
        return ByteBuffer.wrap(body);
    }

    private ByteBuffer exactly(int bodyBytes, int expected, String type) throws IOException {
        if (bodyBytes != expected) {
            throw new ProtocolException(CloseReason.MALFORMED_FRAME, type + " body of " + bodyBytes
                    + " bytes instead of " + expected);
        }
        return body(bodyBytes);
    }

    private static String string(ByteBuffer body, String field) throws ProtocolException {
        int length = Short.toUnsignedInt(body.getShort());
        if (length > body.remaining()) {
            throw new ProtocolException(CloseReason.MALFORMED_FRAME, field + " claims " + length + " bytes, "
                    + body.remaining() + " remain");
        }
        ByteBuffer slice = body.slice(body.position(), length);
        body.position(body.position() + length);
        try {
            return StandardCharsets.UTF_8.newDecoder()
                    .onMalformedInput(CodingErrorAction.REPORT)
                    .onUnmappableCharacter(CodingErrorAction.REPORT)
                    .decode(slice).toString();
        } catch (CharacterCodingException e) {
            throw new ProtocolException(CloseReason.MALFORMED_FRAME, field + " is not valid UTF-8", e);
        }
    }

    private static void requireEnd(ByteBuffer body, String type) throws ProtocolException {
        if (body.hasRemaining()) {
            throw new ProtocolException(CloseReason.MALFORMED_FRAME, type + " has " + body.remaining()
                    + " unexpected trailing bytes");
        }
    }
}
