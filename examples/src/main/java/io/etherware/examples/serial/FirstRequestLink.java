package io.etherware.examples.serial;

import io.etherware.pendulum.serial.SerialLink;
import java.io.IOException;

/**
 * A serial link that can wait for the host's first bytes before the board starts, then hands
 * those bytes to the board's first read, so the host's first request is served rather than lost.
 * One reader and one writer thread, as {@link SerialLink} allows; {@link #awaitFirstBytes} is
 * called before the board starts reading.
 */
final class FirstRequestLink implements SerialLink {

    private static final long POLL_NS = 100_000_000L;

    private final SerialLink link;
    private final byte[] held = new byte[256];
    private int heldFrom;
    private int heldTo;

    FirstRequestLink(SerialLink link) {
        this.link = link;
    }

    /**
     * Waits until the host writes something, polling every 100 ms, and keeps what arrived for the
     * first read.
     *
     * @param stillWanted asked between polls; false ends the wait
     * @return true once bytes arrived, false if the wait was ended first
     * @throws IOException if the link fails
     */
    boolean awaitFirstBytes(java.util.function.BooleanSupplier stillWanted) throws IOException {
        while (stillWanted.getAsBoolean()) {
            int read = link.read(held, 0, held.length, POLL_NS);
            if (read > 0) {
                heldFrom = 0;
                heldTo = read;
                return true;
            }
        }
        return false;
    }

    @Override
    public String name() {
        return link.name();
    }

    @Override
    public void write(byte[] data, int offset, int length) throws IOException {
        link.write(data, offset, length);
    }

    @Override
    public int read(byte[] buffer, int offset, int length, long timeoutNs) throws IOException {
        if (heldFrom < heldTo) {
            int count = Math.min(length, heldTo - heldFrom);
            System.arraycopy(held, heldFrom, buffer, offset, count);
            heldFrom += count;
            return count;
        }
        return link.read(buffer, offset, length, timeoutNs);
    }

    @Override
    public void close() {
        link.close();
    }
}
