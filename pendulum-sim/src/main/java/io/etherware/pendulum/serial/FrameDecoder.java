package io.etherware.pendulum.serial;

/**
 * A streaming decoder of {@link DspProtocol} frames from a byte stream that may hold garbage,
 * flipped bits and lost bytes.
 *
 * <p>It hunts for the start byte, checks that the type is known and the length is the type's
 * length, waits for the whole frame, and checks the CRC. On any failure it counts a reject and
 * resumes the hunt at the byte after the rejected start byte, so a genuine frame that began
 * inside the rejected bytes is still found. Only whole, CRC-valid frames of a known type and
 * length reach the {@link Listener}: a bad frame is never acted upon. It never throws on input.
 *
 * <p>Allocation-free. Not thread-safe: one reader thread feeds it.
 */
public final class FrameDecoder {

    /** A decoder hunting for its first start byte, with no counts yet. */
    public FrameDecoder() {
    }

    /** Receives each valid frame. */
    @FunctionalInterface
    public interface Listener {
        /**
         * Called on the feeding thread for each valid frame. {@code payload} is the decoder's own
         * buffer: read it before returning, do not keep it.
         *
         * @param type    the message type, a known one of {@link DspProtocol}
         * @param payload the buffer holding the payload
         * @param offset  where the payload starts in {@code payload}
         * @param length  the payload's length, the type's payload size
         */
        void onFrame(int type, byte[] payload, int offset, int length);
    }

    private final byte[] buffer = new byte[DspProtocol.MAX_FRAME_BYTES];
    private int count;
    private long framesAccepted;
    private long framesRejected;
    private long bytesDiscarded;

    /**
     * Feeds received bytes; calls {@code listener} for every complete valid frame among them. A
     * frame may span several calls.
     *
     * @param data     the received bytes
     * @param offset   where they start in {@code data}
     * @param length   how many there are, 0 or more
     * @param listener receives each valid frame, on this thread; an exception it throws propagates
     *                 to the caller after its frame is consumed
     */
    public void accept(byte[] data, int offset, int length, Listener listener) {
        for (int i = offset; i < offset + length; i++) {
            buffer[count++] = data[i];
            drain(listener);
        }
    }

    /** Processes as much of the buffer as possible. */
    private void drain(Listener listener) {
        while (count > 0) {
            if ((buffer[0] & 0xFF) != DspProtocol.START) {
                int start = 1;
                while (start < count && (buffer[start] & 0xFF) != DspProtocol.START) {
                    start++;
                }
                bytesDiscarded += start;
                shift(start);
                continue;
            }
            if (count < DspProtocol.HEADER_BYTES) {
                return;
            }
            int type = buffer[1] & 0xFF;
            int length = buffer[2] & 0xFF;
            if (DspProtocol.payloadBytes(type) != length) {
                reject();
                continue;
            }
            int frameBytes = DspProtocol.OVERHEAD_BYTES + length;
            if (count < frameBytes) {
                return;
            }
            int expected = Crc16.of(buffer, 1, 2 + length);
            int received = DspProtocol.getU16(buffer, DspProtocol.HEADER_BYTES + length);
            if (expected != received) {
                reject();
                continue;
            }
            framesAccepted++;
            try {
                listener.onFrame(type, buffer, DspProtocol.HEADER_BYTES, length);
            } finally {
                shift(frameBytes);
            }
        }
    }

    /** Drops the start byte of a bad frame and hunts again from the next byte. */
    private void reject() {
        framesRejected++;
        bytesDiscarded++;
        shift(1);
    }

    private void shift(int bytes) {
        System.arraycopy(buffer, bytes, buffer, 0, count - bytes);
        count -= bytes;
    }

    /** Forgets a partial frame (e.g. after a link reset); counters are kept. */
    public void reset() {
        count = 0;
    }

    /**
     * Valid frames delivered.
     *
     * @return the count since construction
     */
    public long framesAccepted() {
        return framesAccepted;
    }

    /**
     * Candidate frames rejected: unknown type, wrong length or bad CRC.
     *
     * @return the count since construction
     */
    public long framesRejected() {
        return framesRejected;
    }

    /**
     * Bytes skipped while hunting for a start byte, including rejected start bytes.
     *
     * @return the count since construction
     */
    public long bytesDiscarded() {
        return bytesDiscarded;
    }

    /**
     * Bytes held waiting for the rest of a frame.
     *
     * @return the count, in [0, {@value DspProtocol#MAX_FRAME_BYTES})
     */
    public int bufferedBytes() {
        return count;
    }
}
