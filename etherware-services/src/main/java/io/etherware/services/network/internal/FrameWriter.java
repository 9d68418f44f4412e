package io.etherware.services.network.internal;

import io.etherware.core.message.Profile;
import java.io.BufferedOutputStream;
import java.io.DataOutputStream;
import java.io.IOException;
import java.io.OutputStream;
import java.nio.charset.StandardCharsets;
import java.util.List;

/**
 * Writes frames to one connection through a buffer; {@link #flush()} sends them.
 *
 * <p>Not thread-safe: the connection's writer thread owns it (the handshake thread before it).
 */
final class FrameWriter {

    private static final int BUFFER_BYTES = 64 * 1024;
    /** Longest string field: its length is an unsigned 16-bit number. */
    static final int MAX_STRING_BYTES = 0xFFFF;

    private final DataOutputStream out;
    private long bytes;

    FrameWriter(OutputStream output) {
        this.out = new DataOutputStream(new BufferedOutputStream(output, BUFFER_BYTES));
    }

    void hello(Frame.Hello hello) throws IOException {
        byte[] nodeId = utf8(hello.nodeId());
        begin(Frame.HELLO, 4 + 2 + 2 + nodeId.length + 8 + 8 + 4 + 1 + 1);
        out.writeInt(Frame.MAGIC);
        out.writeShort(hello.version());
        string(nodeId);
        out.writeLong(hello.incarnation());
        out.writeLong(hello.epochNs());
        out.writeInt(hello.maxFrameBytes());
        out.writeByte(hello.lanes());
        out.writeByte(hello.lane());
    }

    void resume(Frame.Resume resume) throws IOException {
        begin(Frame.RESUME, 24);
        out.writeLong(resume.streamId());
        out.writeLong(resume.knownStreamId());
        out.writeLong(resume.receivedCount());
    }

    void data(long seq, long ack, int hops, byte[] xml) throws IOException {
        begin(Frame.DATA, Frame.DATA_OVERHEAD_BYTES - 1 + xml.length);
        out.writeLong(seq);
        out.writeLong(ack);
        out.writeByte(hops);
        out.write(xml);
    }

    void ack(long count) throws IOException {
        begin(Frame.ACK, 8);
        out.writeLong(count);
    }

    void sync() throws IOException {
        begin(Frame.SYNC, 0);
    }

    void heartbeat() throws IOException {
        begin(Frame.HEARTBEAT, 0);
    }

    /** The announce body, encoded once and written to every peer. */
    static byte[] announceBody(long version, List<Profile> profiles) {
        try (var bytes = new java.io.ByteArrayOutputStream(64 + 32 * profiles.size());
             var body = new DataOutputStream(bytes)) {
            body.writeLong(version);
            body.writeInt(profiles.size());
            for (Profile profile : profiles) {
                byte[] text = utf8(profile.toString());
                body.writeShort(text.length);
                body.write(text);
            }
            body.flush();
            return bytes.toByteArray();
        } catch (IOException e) {
            throw new IllegalStateException("writing to memory failed", e);
        }
    }

    void announce(byte[] body) throws IOException {
        begin(Frame.ANNOUNCE, body.length);
        out.write(body);
    }

    void timeRequest(long t1) throws IOException {
        begin(Frame.TIME_REQUEST, 8);
        out.writeLong(t1);
    }

    void timeReply(long t1, long t2, long t3) throws IOException {
        begin(Frame.TIME_REPLY, 24);
        out.writeLong(t1);
        out.writeLong(t2);
        out.writeLong(t3);
    }

    void reject(long seq, String reason) throws IOException {
        byte[] text = utf8(truncate(reason));
        begin(Frame.REJECT, 8 + 2 + text.length);
        out.writeLong(seq);
        string(text);
    }

    void bye(int code, String reason) throws IOException {
        byte[] text = utf8(truncate(reason));
        begin(Frame.BYE, 1 + 2 + text.length);
        out.writeByte(code);
        string(text);
    }

    void flush() throws IOException {
        out.flush();
    }

    /** Bytes framed on this connection so far, buffered or sent. */
    long bytes() {
        return bytes;
    }

    private void begin(byte type, int bodyBytes) throws IOException {
        out.writeInt(1 + bodyBytes);
        out.writeByte(type);
        bytes += 5L + bodyBytes;
    }

    private void string(byte[] utf8) throws IOException {
        out.writeShort(utf8.length);
        out.write(utf8);
    }

    private static byte[] utf8(String text) {
        byte[] bytes = text.getBytes(StandardCharsets.UTF_8);
        if (bytes.length > MAX_STRING_BYTES) {
            throw new IllegalArgumentException("string of " + bytes.length + " UTF-8 bytes is over " + MAX_STRING_BYTES);
        }
        return bytes;
    }

    /** Reasons are for logs: keep them short enough for a string field, on a code point boundary. */
    private static String truncate(String text) {
        if (text.length() <= 1000) {
            return text;
        }
        int end = Character.isHighSurrogate(text.charAt(999)) ? 999 : 1000;
        return text.substring(0, end) + "...";
    }
}
