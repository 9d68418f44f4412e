package io.etherware.services.network;

import java.io.ByteArrayOutputStream;
import java.io.DataInputStream;
import java.io.DataOutputStream;
import java.io.EOFException;
import java.io.IOException;
import java.net.InetSocketAddress;
import java.net.Socket;
import java.net.SocketException;
import java.nio.charset.StandardCharsets;
import java.util.ArrayList;
import java.util.List;

/**
 * A peer written straight from {@code NETWORK-PROTOCOL.md} with a raw socket: the attacker of the
 * bad-input tests, and a check that the document is enough to talk to a node.
 */
final class RawPeer implements AutoCloseable {

    static final int MAGIC = 0x45575254;
    static final byte HELLO = 1;
    /** The protocol version this peer speaks. */
    static final int VERSION = 3;
    static final byte RESUME = 2;
    static final byte DATA = 3;
    static final byte ACK = 4;
    static final byte HEARTBEAT = 5;
    static final byte ANNOUNCE = 6;
    static final byte REJECT = 9;
    static final byte BYE = 10;

    /** A frame read back: its type and body. */
    record Received(int type, byte[] body) {
        int byeCode() {
            return body[0] & 0xFF;
        }

        String byeText() {
            return new String(body, 3, body.length - 3, StandardCharsets.UTF_8);
        }
    }

    private final Socket socket;
    private final DataOutputStream out;
    private final DataInputStream in;
    /** The incarnation its HELLO names: one process of the node. */
    long incarnation = 0x1234_5678_9abcL;

    RawPeer(InetSocketAddress node) throws IOException {
        this(connected(node));
    }

    /** A raw peer over a socket already connected (e.g. a TLS one). */
    RawPeer(Socket connected) throws IOException {
        socket = connected;
        socket.setSoTimeout(30_000);
        out = new DataOutputStream(socket.getOutputStream());
        in = new DataInputStream(socket.getInputStream());
    }

    private static Socket connected(InetSocketAddress node) throws IOException {
        var socket = new Socket();
        socket.connect(node, 10_000);
        return socket;
    }

    void raw(byte[] bytes) throws IOException {
        out.write(bytes);
        out.flush();
    }

    void frame(int type, byte[] body) throws IOException {
        out.writeInt(1 + body.length);
        out.writeByte(type);
        out.write(body);
        out.flush();
    }

    static byte[] body(IoWriter writer) throws IOException {
        var bytes = new ByteArrayOutputStream();
        var data = new DataOutputStream(bytes);
        writer.write(data);
        data.flush();
        return bytes.toByteArray();
    }

    @FunctionalInterface
    interface IoWriter {
        void write(DataOutputStream out) throws IOException;
    }

    static void string(DataOutputStream out, String text) throws IOException {
        byte[] utf8 = text.getBytes(StandardCharsets.UTF_8);
        out.writeShort(utf8.length);
        out.write(utf8);
    }

    void hello(int magic, int version, String nodeId) throws IOException {
        hello(magic, version, nodeId, 0);
    }

    /** A HELLO that dials {@code lane} of the two lanes the nodes under test run. */
    void hello(int magic, int version, String nodeId, int lane) throws IOException {
        frame(HELLO, body(out -> {
            out.writeInt(magic);
            out.writeShort(version);
            string(out, nodeId);
            out.writeLong(incarnation);
            out.writeLong(System.currentTimeMillis() * 1_000_000L);
            out.writeInt(1 << 20);
            out.writeByte(2); // lanes, as the nodes under test run
            out.writeByte(lane);
        }));
    }

    /** A complete handshake as {@code nodeId} on stream 1, knowing nothing of the node. */
    void handshake(String nodeId) throws IOException {
        hello(MAGIC, VERSION, nodeId);
        expect(HELLO);
        frame(RESUME, body(out -> {
            out.writeLong(1);
            out.writeLong(0);
            out.writeLong(0);
        }));
        expect(RESUME);
    }

    /**
     * A handshake that reads the node's RESUME first and then claims to have received
     * {@code claimed} messages of stream {@code streamId} (0: the node's current stream); returns
     * the node's stream id.
     */
    long handshakeClaiming(String nodeId, long streamId, long claimed) throws IOException {
        hello(MAGIC, VERSION, nodeId);
        expect(HELLO);
        long nodeStreamId = java.nio.ByteBuffer.wrap(expect(RESUME).body()).getLong();
        frame(RESUME, body(out -> {
            out.writeLong(1);
            out.writeLong(streamId == 0 ? nodeStreamId : streamId);
            out.writeLong(claimed);
        }));
        return nodeStreamId;
    }

    /** Where the node's streams with this peer stand, from its RESUME. */
    record Resume(long streamId, long knownStreamId, long receivedCount) {
    }

    /** Sends HELLO as {@code nodeId}, reads the node's HELLO and RESUME; our RESUME is the caller's to send. */
    Resume introduce(String nodeId) throws IOException {
        hello(MAGIC, VERSION, nodeId);
        expect(HELLO);
        var body = java.nio.ByteBuffer.wrap(expect(RESUME).body());
        return new Resume(body.getLong(), body.getLong(), body.getLong());
    }

    void resume(long streamId, long knownStreamId, long receivedCount) throws IOException {
        frame(RESUME, body(out -> {
            out.writeLong(streamId);
            out.writeLong(knownStreamId);
            out.writeLong(receivedCount);
        }));
    }

    void ack(long count) throws IOException {
        frame(ACK, body(out -> out.writeLong(count)));
    }

    void heartbeat() throws IOException {
        frame(HEARTBEAT, new byte[0]);
    }

    void announce(long version, String... profiles) throws IOException {
        frame(ANNOUNCE, body(out -> {
            out.writeLong(version);
            out.writeInt(profiles.length);
            for (String profile : profiles) {
                string(out, profile);
            }
        }));
    }

    void bye(int code, String text) throws IOException {
        frame(BYE, body(out -> {
            out.writeByte(code);
            string(out, text);
        }));
    }

    /** A message frame with every header field chosen by the caller. */
    void data(long seq, long ack, int hops, byte[] xml) throws IOException {
        frame(DATA, body(out -> {
            out.writeLong(seq);
            out.writeLong(ack);
            out.writeByte(hops);
            out.write(xml);
        }));
    }

    /** The seq of a DATA frame read back. */
    static long dataSeq(Received frame) {
        return java.nio.ByteBuffer.wrap(frame.body()).getLong();
    }

    /** The message XML of a DATA frame read back. */
    static String dataXml(Received frame) {
        return new String(frame.body(), 17, frame.body().length - 17, StandardCharsets.UTF_8);
    }

    void soTimeoutMs(int ms) throws IOException {
        socket.setSoTimeout(ms);
    }

    void data(long seq, String xml) throws IOException {
        frame(DATA, body(out -> {
            out.writeLong(seq);
            out.writeLong(0);
            out.writeByte(0);
            out.write(xml.getBytes(StandardCharsets.UTF_8));
        }));
    }

    Received read() throws IOException {
        int length = in.readInt();
        int type = in.readUnsignedByte();
        byte[] body = new byte[length - 1];
        in.readFully(body);
        return new Received(type, body);
    }

    Received expect(int type) throws IOException {
        Received frame = read();
        if (frame.type() != type) {
            throw new AssertionError("expected frame type " + type + ", got " + frame.type());
        }
        return frame;
    }

    /** Reads until the node closes the connection; returns every frame it sent meanwhile. */
    List<Received> readUntilClosed() throws IOException {
        var frames = new ArrayList<Received>();
        while (true) {
            try {
                frames.add(read());
            } catch (EOFException e) {
                return frames;
            } catch (SocketException e) {
                return frames; // reset: closed as well
            }
        }
    }

    /**
     * Reads raw bytes until the node closes (at most {@code limit} kept), for a node that may not
     * answer in frames at all (a TLS port answering plain TCP with an alert).
     */
    byte[] readRawUntilClosed(int limit) throws IOException {
        var kept = new ByteArrayOutputStream();
        byte[] chunk = new byte[4096];
        while (true) {
            int read;
            try {
                read = in.read(chunk);
            } catch (SocketException e) {
                read = -1; // reset: closed as well
            }
            if (read < 0) {
                return kept.toByteArray();
            }
            kept.write(chunk, 0, Math.min(read, Math.max(0, limit - kept.size())));
        }
    }

    void shutdownOutput() throws IOException {
        socket.shutdownOutput();
    }

    @Override
    public void close() throws IOException {
        socket.close();
    }
}
