package io.etherware.pendulum.serial;

import com.fazecast.jSerialComm.SerialPort;
import com.fazecast.jSerialComm.SerialPortInvalidPortException;
import java.io.IOException;
import java.util.concurrent.locks.LockSupport;

/**
 * A {@link SerialLink} on a real serial port through jSerialComm (8 data bits, no parity, one stop
 * bit, no flow control).
 *
 * <p>The port is opened non-blocking and a waiting read polls {@code bytesAvailable()} every
 * {@link #POLL_INTERVAL_NS} while sleeping in between: jSerialComm's own read timeouts are
 * termios {@code VTIME} tenths of a second on some platforms, far too coarse for a 15 ms loop.
 * Writes block until the bytes are handed to the driver. Threading: the {@link SerialLink}
 * contract.
 */
public final class JSerialCommLink implements SerialLink {

    /** How often a waiting read looks for bytes, 100 µs (about one byte at 115200 baud). */
    public static final long POLL_INTERVAL_NS = 100_000L;

    private final SerialPort port;
    private final String path;
    private volatile boolean closed;

    private JSerialCommLink(SerialPort port, String path) {
        this.port = port;
        this.path = path;
    }

    /**
     * Opens {@code portPath} (e.g. {@code /dev/ttyUSB0}, {@code COM3}, a pseudo-terminal slave) at
     * {@code baudRate} 8N1, without flow control. Call it at start, not on a real-time thread.
     *
     * @param portPath the port's name or path, e.g. {@code /dev/ttyUSB0}
     * @param baudRate bits per second, greater than 0, e.g. 115200
     * @return the open link; close it when done
     * @throws IOException naming the port and jSerialComm's error code and location
     * @throws IllegalArgumentException when {@code baudRate} is not positive
     */
    public static JSerialCommLink open(String portPath, int baudRate) throws IOException {
        if (baudRate <= 0) {
            throw new IllegalArgumentException("baudRate=" + baudRate + ": must be > 0");
        }
        SerialPort port;
        try {
            port = SerialPort.getCommPort(portPath);
        } catch (SerialPortInvalidPortException e) {
            throw new IOException("no serial port at " + portPath + ": " + e.getMessage(), e);
        }
        port.setComPortParameters(baudRate, 8, SerialPort.ONE_STOP_BIT, SerialPort.NO_PARITY);
        port.setFlowControl(SerialPort.FLOW_CONTROL_DISABLED);
        port.setComPortTimeouts(SerialPort.TIMEOUT_NONBLOCKING | SerialPort.TIMEOUT_WRITE_BLOCKING, 0, 0);
        // No "safety sleep": the DSP board does not reset when the port opens.
        if (!port.openPort(0)) {
            throw new IOException("cannot open serial port " + portPath + " at " + baudRate
                    + " baud: jSerialComm error " + port.getLastErrorCode() + " at native line "
                    + port.getLastErrorLocation() + " (check the path and permissions)");
        }
        return new JSerialCommLink(port, portPath);
    }

    @Override
    public String name() {
        return path;
    }

    @Override
    public void write(byte[] data, int offset, int length) throws IOException {
        ensureOpen();
        int written = port.writeBytes(data, length, offset);
        if (written != length) {
            throw new IOException("wrote " + written + " of " + length + " bytes to " + path
                    + " (jSerialComm error " + port.getLastErrorCode() + ")");
        }
    }

    @Override
    public int read(byte[] buffer, int offset, int length, long timeoutNs) throws IOException {
        ensureOpen();
        long deadlineNs = System.nanoTime() + timeoutNs;
        while (true) {
            int available = port.bytesAvailable();
            if (available < 0) {
                throw new IOException(path + " is gone (disconnected or closed)");
            }
            if (available > 0) {
                int n = port.readBytes(buffer, Math.min(available, length), offset);
                if (n < 0) {
                    throw new IOException("read from " + path + " failed (jSerialComm error "
                            + port.getLastErrorCode() + ")");
                }
                if (n > 0) {
                    return n;
                }
            }
            long remainingNs = deadlineNs - System.nanoTime();
            if (remainingNs <= 0) {
                return 0;
            }
            LockSupport.parkNanos(Math.min(remainingNs, POLL_INTERVAL_NS));
            ensureOpen();
        }
    }

    private void ensureOpen() throws IOException {
        if (closed) {
            throw new IOException(path + " is closed");
        }
    }

    /** Closes the port. Idempotent. */
    @Override
    public void close() {
        if (!closed) {
            closed = true;
            port.closePort();
        }
    }
}
