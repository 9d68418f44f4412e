package io.etherware.pendulum.serial;

import java.io.IOException;

/**
 * One end of a byte-oriented, full-duplex serial line: a UART port, or one end of a simulated
 * or pseudo-terminal pair.
 *
 * <p>Threading: one thread may read while another writes; reads are not to be called from two
 * threads at once, nor writes. Bytes carry no framing: {@link FrameDecoder} finds the frames.
 */
public interface SerialLink extends AutoCloseable {

    /**
     * A name for logs and errors.
     *
     * @return e.g. the port path
     */
    String name();

    /**
     * Queues bytes for transmission and returns without waiting for them to be on the wire.
     *
     * @param data   the bytes
     * @param offset where they start in {@code data}
     * @param length how many to send
     * @throws IOException if the link is closed or the port failed
     */
    void write(byte[] data, int offset, int length) throws IOException;

    /**
     * Reads the bytes that have arrived, waiting up to {@code timeoutNs} for the first one.
     *
     * @param buffer    receives the bytes
     * @param offset    where to put the first one in {@code buffer}
     * @param length    the most bytes to read
     * @param timeoutNs how long to wait for the first byte, in nanoseconds; 0 to return at once
     * @return the number of bytes read, 0 if none arrived within the timeout
     * @throws IOException if the link is closed or the port failed
     */
    int read(byte[] buffer, int offset, int length, long timeoutNs) throws IOException;

    /** Closes this end; idempotent. */
    @Override
    void close();
}
