package io.etherware.pendulum.serial;

import io.etherware.pendulum.serial.internal.PseudoTerminal;
import java.io.IOException;

/**
 * The master side of a new pseudo-terminal (Linux), as a {@link SerialLink}: a DSP board
 * simulator serves it, and a node opens the other side, {@link #slavePath()}, as any serial port
 * ({@link JSerialCommLink#open}), so the node's serial stack runs as it would with real hardware.
 * Raw mode: bytes pass untranslated.
 *
 * <p>Thread-safety: one reader and one writer thread at a time; {@link #close} from any thread.
 */
public final class PseudoTerminalLink implements SerialLink {

    private final PseudoTerminal pty;

    private PseudoTerminalLink(PseudoTerminal pty) {
        this.pty = pty;
    }

    /**
     * Opens a new pseudo-terminal pair. Uses libc through the FFM API (see the module's notes on
     * native access).
     *
     * @return its master side
     * @throws IOException naming the libc call and errno that failed
     */
    public static PseudoTerminalLink open() throws IOException {
        return new PseudoTerminalLink(PseudoTerminal.open());
    }

    /** {@return the slave's device path, e.g. {@code /dev/pts/3}: open it as a serial port} */
    public String slavePath() {
        return pty.slavePath();
    }

    @Override
    public String name() {
        return pty.name();
    }

    @Override
    public void write(byte[] data, int offset, int length) throws IOException {
        pty.write(data, offset, length);
    }

    @Override
    public int read(byte[] buffer, int offset, int length, long timeoutNs) throws IOException {
        return pty.read(buffer, offset, length, timeoutNs);
    }

    @Override
    public void close() {
        pty.close();
    }
}
