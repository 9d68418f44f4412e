package io.etherware.services.recording;

import java.io.DataOutputStream;
import java.io.IOException;
import java.nio.charset.StandardCharsets;

/**
 * The recording file's layout (RECORDING.md): a header, then one record per message, all numbers
 * big-endian.
 *
 * <pre>
 * header: magic "EWRC" (4 bytes), version u16 = 1, start i64 (epoch ns of the recording node's
 *         clock), node id: u16 length + UTF-8 bytes
 * record: offset i64 (ns since the start, on the node's monotonic clock, never decreasing),
 *         length i32 (1 .. the codec's document limit), then that many bytes: the message's XML
 *         document (MessageCodec, UTF-8)
 * </pre>
 * The file ends at a record boundary.
 */
final class RecordingFormat {

    static final byte[] MAGIC = "EWRC".getBytes(StandardCharsets.US_ASCII);
    static final int VERSION = 1;
    /** Bytes before the first record's offset, besides the node id's. */
    static final int FIXED_HEADER_BYTES = MAGIC.length + 2 + 8 + 2;
    static final int RECORD_HEADER_BYTES = 8 + 4;

    private RecordingFormat() {
    }

    static void writeHeader(DataOutputStream out, String nodeId, long startEpochNs) throws IOException {
        out.write(MAGIC);
        out.writeShort(VERSION);
        out.writeLong(startEpochNs);
        byte[] id = nodeId.getBytes(StandardCharsets.UTF_8);
        out.writeShort(id.length);
        out.write(id);
    }

    static void writeRecord(DataOutputStream out, long offsetNs, byte[] document) throws IOException {
        out.writeLong(offsetNs);
        out.writeInt(document.length);
        out.write(document);
    }
}
