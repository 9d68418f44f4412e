package io.etherware.services.recording;

import io.etherware.core.codec.MessageCodec;
import io.etherware.core.kernel.Kernel;
import io.etherware.core.message.ContentsTypes;
import io.etherware.core.message.Message;
import java.io.BufferedInputStream;
import java.io.DataInputStream;
import java.io.EOFException;
import java.io.IOException;
import java.io.InputStream;
import java.nio.charset.StandardCharsets;
import java.nio.file.Files;
import java.nio.file.Path;
import java.util.ArrayList;
import java.util.Arrays;
import java.util.HexFormat;
import java.util.List;
import java.util.Objects;
import java.util.concurrent.locks.LockSupport;

/**
 * A recording a {@link Recorder} wrote, read back and checked: which node recorded it, when, and
 * the messages with their offsets from the start. {@link #replay} sends them into a node again.
 *
 * <p>Immutable; safe to share between threads.
 */
public final class Recording {

    /**
     * One recorded message.
     *
     * @param offsetNs when it was sent, in nanoseconds after the recording started (the recording
     *                 node's monotonic clock)
     * @param message  the message as it was sent: profile, sender, time stamp, QoS, contents, ids
     */
    public record Recorded(long offsetNs, Message message) {

        /** Checks the message is given. */
        public Recorded {
            Objects.requireNonNull(message, "message");
        }
    }

    private final String nodeId;
    private final long startEpochNs;
    private final List<Recorded> messages;

    private Recording(String nodeId, long startEpochNs, List<Recorded> messages) {
        this.nodeId = nodeId;
        this.startEpochNs = startEpochNs;
        this.messages = List.copyOf(messages);
    }

    /**
     * Reads and checks a recording; every record must decode with {@code types} (register the
     * recorded contents types first).
     *
     * @param file  a file a {@link Recorder} wrote
     * @param types the contents types to decode the messages with
     * @return the recording
     * @throws IOException if the file cannot be read, or is not a complete recording of this format;
     *                     the message names the record and its byte position, and what was wrong
     */
    public static Recording read(Path file, ContentsTypes types) throws IOException {
        Objects.requireNonNull(types, "types");
        var codec = new MessageCodec(types);
        try (InputStream raw = new BufferedInputStream(Files.newInputStream(file))) {
            var in = new Counting(raw);
            var data = new DataInputStream(in);
            String where = "recording " + file;
            byte[] magic = new byte[RecordingFormat.MAGIC.length];
            int got = data.readNBytes(magic, 0, magic.length);
            if (got < magic.length || !Arrays.equals(magic, RecordingFormat.MAGIC)) {
                throw new IOException(where + " is not an Etherware recording: it starts with "
                        + HexFormat.ofDelimiter(" ").formatHex(magic, 0, got) + ", not the magic \"EWRC\"");
            }
            int version;
            long startEpochNs;
            String nodeId;
            try {
                version = data.readUnsignedShort();
                if (version != RecordingFormat.VERSION) {
                    throw new IOException(where + " has format version " + version + "; this build reads version "
                            + RecordingFormat.VERSION);
                }
                startEpochNs = data.readLong();
                byte[] id = data.readNBytes(data.readUnsignedShort());
                nodeId = new String(id, StandardCharsets.UTF_8);
            } catch (EOFException e) {
                throw new IOException(where + " ends inside its header (" + in.position + " bytes)", e);
            }
            var messages = new ArrayList<Recorded>();
            long lastOffsetNs = 0;
            while (true) {
                long at = in.position;
                int index = messages.size() + 1;
                long offsetNs;
                try {
                    offsetNs = data.readLong();
                } catch (EOFException e) {
                    if (in.position == at) {
                        break; // the end, at a record boundary
                    }
                    throw truncated(where, index, at, in.position - at, RecordingFormat.RECORD_HEADER_BYTES, e);
                }
                int length;
                try {
                    length = data.readInt();
                } catch (EOFException e) {
                    throw truncated(where, index, at, in.position - at, RecordingFormat.RECORD_HEADER_BYTES, e);
                }
                String record = where + ": record " + index + " at byte " + at;
                if (offsetNs < lastOffsetNs) {
                    throw new IOException(record + " goes back in time: offset " + offsetNs + " ns after "
                            + lastOffsetNs + " ns");
                }
                if (length < 1 || length > codec.maxDocumentBytes()) {
                    throw new IOException(record + " has length " + length + "; a message is 1 to "
                            + codec.maxDocumentBytes() + " bytes");
                }
                byte[] document = data.readNBytes(length);
                if (document.length < length) {
                    throw new IOException(record + " is truncated: its message has " + document.length + " of "
                            + length + " bytes");
                }
                Message message;
                try {
                    message = codec.decode(document);
                } catch (RuntimeException e) {
                    throw new IOException(record + " does not decode: " + e.getMessage(), e);
                }
                messages.add(new Recorded(offsetNs, message));
                lastOffsetNs = offsetNs;
            }
            return new Recording(nodeId, startEpochNs, messages);
        }
    }

    private static IOException truncated(String where, int index, long at, long have, int need, EOFException e) {
        return new IOException(where + ": record " + index + " at byte " + at + " is truncated: its header has "
                + have + " of " + need + " bytes", e);
    }

    /** {@return the id of the node that recorded it} */
    public String nodeId() {
        return nodeId;
    }

    /** {@return when the recording started, epoch nanoseconds of the recording node's clock} */
    public long startEpochNs() {
        return startEpochNs;
    }

    /** {@return the recorded messages, in the order they were sent} */
    public List<Recorded> messages() {
        return messages;
    }

    /**
     * Sends the recorded messages into {@code node} again, in order, each at its offset from the
     * start of the replay divided by {@code speed} (the calling thread sleeps between them). Each
     * goes to its recorded profile with its recorded QoS and contents, as a new message of
     * {@code node}: a new id, time-stamped now, and without a sender or a correlation id, so a
     * recorded request arrives as a one-way message and nothing answers back into the replay.
     * Run it on a thread of your own, never on a dispatcher.
     *
     * @param node  the node to send into (started)
     * @param speed 1 for the recorded pace, 2 for twice as fast; &gt; 0
     * @return how many messages were sent
     * @throws IllegalArgumentException if {@code speed} is not positive and finite
     * @throws InterruptedException     if interrupted between two messages (those before were sent)
     */
    public int replay(Kernel node, double speed) throws InterruptedException {
        Objects.requireNonNull(node, "node");
        if (!(speed > 0) || Double.isInfinite(speed)) {
            throw new IllegalArgumentException("speed=" + speed + " must be > 0 and finite (1 = as recorded)");
        }
        long startNs = node.clock().nanoTime();
        int sent = 0;
        for (Recorded recorded : messages) {
            long dueNs = startNs + (long) (recorded.offsetNs() / speed);
            for (long waitNs = dueNs - node.clock().nanoTime(); waitNs > 0; waitNs = dueNs - node.clock().nanoTime()) {
                LockSupport.parkNanos(waitNs);
                if (Thread.interrupted()) {
                    throw new InterruptedException("replay interrupted after " + sent + " of " + messages.size()
                            + " messages");
                }
            }
            Message original = recorded.message();
            node.send(new Message(original.profile(), null, node.clock().epochNanos(), original.qos(),
                    original.contents(), node.newMessageId(), null));
            sent++;
        }
        return sent;
    }

    @Override
    public String toString() {
        return "recording of node '" + nodeId + "': " + messages.size() + " messages";
    }

    /** Counts the bytes read, for the positions in error messages. */
    private static final class Counting extends InputStream {
        private final InputStream in;
        long position;

        Counting(InputStream in) {
            this.in = in;
        }

        @Override
        public int read() throws IOException {
            int b = in.read();
            if (b >= 0) {
                position++;
            }
            return b;
        }

        @Override
        public int read(byte[] buffer, int offset, int length) throws IOException {
            int n = in.read(buffer, offset, length);
            if (n > 0) {
                position += n;
            }
            return n;
        }
    }
}
