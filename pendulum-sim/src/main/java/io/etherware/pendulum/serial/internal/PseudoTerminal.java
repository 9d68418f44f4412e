package io.etherware.pendulum.serial.internal;

import io.etherware.pendulum.serial.SerialLink;
import java.io.IOException;
import java.lang.foreign.Arena;
import java.lang.foreign.FunctionDescriptor;
import java.lang.foreign.Linker;
import java.lang.foreign.MemoryLayout;
import java.lang.foreign.MemorySegment;
import java.lang.foreign.SymbolLookup;
import java.lang.foreign.ValueLayout;
import java.lang.invoke.MethodHandle;
import java.lang.invoke.VarHandle;
import java.nio.charset.StandardCharsets;
import java.util.concurrent.locks.LockSupport;

/**
 * The master side of a Linux pseudo-terminal pair, opened through the Foreign Function & Memory
 * API ({@code posix_openpt}, {@code grantpt}, {@code unlockpt}, {@code ptsname_r}) and put in raw
 * mode ({@code tcgetattr}, {@code cfmakeraw}, {@code tcsetattr}). The slave side at
 * {@link #slavePath()} behaves like a serial port that any program — jSerialComm included — can
 * open; what it writes the master reads, and the reverse. This lets the real serial stack be
 * tested with the DSP simulator and no hardware.
 *
 * <p>Needs native access ({@code --enable-native-access}). Linux only. Threading: the
 * {@link SerialLink} contract (one reader and one writer thread at a time).
 */
public final class PseudoTerminal implements SerialLink {

    private static final int O_RDWR = 0x2;
    private static final int O_NOCTTY = 0x100;
    private static final int TCSANOW = 0;
    private static final short POLLIN = 0x1;
    private static final short POLLHUP = 0x10;
    private static final int EINTR = 4;
    private static final int EIO = 5;
    private static final int EAGAIN = 11;
    private static final int BUFFER_BYTES = 4096;
    /** glibc's struct termios is 60 bytes on Linux; leave room for any ABI. */
    private static final long TERMIOS_BYTES = 256;
    private static final long IDLE_WAIT_NS = 1_000_000L;

    private static final Linker LINKER = Linker.nativeLinker();
    private static final SymbolLookup LIBC = LINKER.defaultLookup();
    private static final MemoryLayout ERRNO_STATE = Linker.Option.captureStateLayout();
    private static final VarHandle ERRNO = ERRNO_STATE.varHandle(
            MemoryLayout.PathElement.groupElement("errno"));
    private static final Linker.Option CAPTURE_ERRNO = Linker.Option.captureCallState("errno");

    private static final MethodHandle POSIX_OPENPT = downcall("posix_openpt",
            FunctionDescriptor.of(ValueLayout.JAVA_INT, ValueLayout.JAVA_INT));
    private static final MethodHandle GRANTPT = downcall("grantpt",
            FunctionDescriptor.of(ValueLayout.JAVA_INT, ValueLayout.JAVA_INT));
    private static final MethodHandle UNLOCKPT = downcall("unlockpt",
            FunctionDescriptor.of(ValueLayout.JAVA_INT, ValueLayout.JAVA_INT));
    private static final MethodHandle PTSNAME_R = downcall("ptsname_r",
            FunctionDescriptor.of(ValueLayout.JAVA_INT, ValueLayout.JAVA_INT, ValueLayout.ADDRESS,
                    ValueLayout.JAVA_LONG));
    private static final MethodHandle TCGETATTR = downcall("tcgetattr",
            FunctionDescriptor.of(ValueLayout.JAVA_INT, ValueLayout.JAVA_INT, ValueLayout.ADDRESS));
    private static final MethodHandle CFMAKERAW = LINKER.downcallHandle(find("cfmakeraw"),
            FunctionDescriptor.ofVoid(ValueLayout.ADDRESS));
    private static final MethodHandle TCSETATTR = downcall("tcsetattr",
            FunctionDescriptor.of(ValueLayout.JAVA_INT, ValueLayout.JAVA_INT, ValueLayout.JAVA_INT,
                    ValueLayout.ADDRESS));
    private static final MethodHandle POLL = downcall("poll",
            FunctionDescriptor.of(ValueLayout.JAVA_INT, ValueLayout.ADDRESS, ValueLayout.JAVA_LONG,
                    ValueLayout.JAVA_INT));
    private static final MethodHandle READ = downcall("read",
            FunctionDescriptor.of(ValueLayout.JAVA_LONG, ValueLayout.JAVA_INT, ValueLayout.ADDRESS,
                    ValueLayout.JAVA_LONG));
    private static final MethodHandle WRITE = downcall("write",
            FunctionDescriptor.of(ValueLayout.JAVA_LONG, ValueLayout.JAVA_INT, ValueLayout.ADDRESS,
                    ValueLayout.JAVA_LONG));
    private static final MethodHandle CLOSE = downcall("close",
            FunctionDescriptor.of(ValueLayout.JAVA_INT, ValueLayout.JAVA_INT));
    private static final MethodHandle STRERROR = LINKER.downcallHandle(find("strerror"),
            FunctionDescriptor.of(ValueLayout.ADDRESS, ValueLayout.JAVA_INT));

    private final int masterFd;
    private final String slavePath;
    private final Arena arena = Arena.ofAuto();
    private final MemorySegment readBuffer = arena.allocate(BUFFER_BYTES);
    private final MemorySegment writeBuffer = arena.allocate(BUFFER_BYTES);
    private final MemorySegment readErrno = arena.allocate(ERRNO_STATE);
    private final MemorySegment writeErrno = arena.allocate(ERRNO_STATE);
    private final MemorySegment pollFd = arena.allocate(8, 4);
    private volatile boolean closed;

    private PseudoTerminal(int masterFd, String slavePath) {
        this.masterFd = masterFd;
        this.slavePath = slavePath;
    }

    /**
     * Opens a new pseudo-terminal pair in raw mode.
     *
     * @throws IOException naming the libc call and errno that failed
     */
    public static PseudoTerminal open() throws IOException {
        try (Arena local = Arena.ofConfined()) {
            MemorySegment errno = local.allocate(ERRNO_STATE);
            int fd = (int) POSIX_OPENPT.invokeExact(errno, O_RDWR | O_NOCTTY);
            if (fd < 0) {
                throw failure("posix_openpt", errno);
            }
            try {
                check("grantpt", (int) GRANTPT.invokeExact(errno, fd), errno);
                check("unlockpt", (int) UNLOCKPT.invokeExact(errno, fd), errno);
                MemorySegment name = local.allocate(256);
                int rc = (int) PTSNAME_R.invokeExact(errno, fd, name, name.byteSize());
                if (rc != 0) {
                    throw new IOException("ptsname_r failed: " + describe(rc));
                }
                String path = name.getString(0, StandardCharsets.US_ASCII);
                MemorySegment termios = local.allocate(TERMIOS_BYTES, 8);
                check("tcgetattr", (int) TCGETATTR.invokeExact(errno, fd, termios), errno);
                CFMAKERAW.invokeExact(termios);
                check("tcsetattr", (int) TCSETATTR.invokeExact(errno, fd, TCSANOW, termios), errno);
                return new PseudoTerminal(fd, path);
            } catch (IOException | RuntimeException | Error e) {
                int ignored = (int) CLOSE.invokeExact(errno, fd);
                throw e;
            }
        } catch (IOException | RuntimeException | Error e) {
            throw e;
        } catch (Throwable t) {
            throw new IOException("pseudo-terminal setup failed: " + t, t);
        }
    }

    /** The slave's device path, e.g. {@code /dev/pts/3}: open it as a serial port. */
    public String slavePath() {
        return slavePath;
    }

    @Override
    public String name() {
        return "pty-master(" + slavePath + ")";
    }

    @Override
    public void write(byte[] data, int offset, int length) throws IOException {
        ensureOpen();
        int done = 0;
        while (done < length) {
            int chunk = Math.min(BUFFER_BYTES, length - done);
            MemorySegment.copy(data, offset + done, writeBuffer, ValueLayout.JAVA_BYTE, 0, chunk);
            long n;
            try {
                n = (long) WRITE.invokeExact(writeErrno, masterFd, writeBuffer, (long) chunk);
            } catch (Throwable t) {
                throw new IOException("write failed on " + name() + ": " + t, t);
            }
            if (n < 0) {
                int errno = (int) ERRNO.get(writeErrno, 0L);
                if (errno == EINTR || errno == EAGAIN) {
                    continue;
                }
                throw new IOException("write on " + name() + " failed: " + describe(errno));
            }
            done += (int) n;
        }
    }

    @Override
    public int read(byte[] buffer, int offset, int length, long timeoutNs) throws IOException {
        ensureOpen();
        long deadlineNs = System.nanoTime() + timeoutNs;
        while (true) {
            long remainingNs = deadlineNs - System.nanoTime();
            int timeoutMs = remainingNs <= 0 ? 0 : (int) Math.min(Integer.MAX_VALUE,
                    (remainingNs + 999_999L) / 1_000_000L);
            short events = poll(timeoutMs);
            boolean hungUp = (events & POLLHUP) != 0;
            if ((events & POLLIN) != 0) {
                int n = readAvailable(buffer, offset, length);
                if (n > 0) {
                    return n;
                }
                hungUp |= n < 0;
            }
            if (hungUp && remainingNs > 0) {
                // No slave open yet (or it was closed): poll() returns at once, so sleep instead.
                LockSupport.parkNanos(Math.min(remainingNs, IDLE_WAIT_NS));
            }
            if (deadlineNs - System.nanoTime() <= 0) {
                return 0;
            }
            ensureOpen();
        }
    }

    /** The returned events of one poll() on the master, or 0 on timeout or EINTR. */
    private short poll(int timeoutMs) throws IOException {
        pollFd.set(ValueLayout.JAVA_INT, 0, masterFd);
        pollFd.set(ValueLayout.JAVA_SHORT, 4, POLLIN);
        pollFd.set(ValueLayout.JAVA_SHORT, 6, (short) 0);
        int rc;
        try {
            rc = (int) POLL.invokeExact(readErrno, pollFd, 1L, timeoutMs);
        } catch (Throwable t) {
            throw new IOException("poll failed on " + name() + ": " + t, t);
        }
        if (rc < 0) {
            int errno = (int) ERRNO.get(readErrno, 0L);
            if (errno == EINTR) {
                return 0;
            }
            throw new IOException("poll on " + name() + " failed: " + describe(errno));
        }
        return rc == 0 ? 0 : pollFd.get(ValueLayout.JAVA_SHORT, 6);
    }

    /** Bytes read, 0 if none after all, -1 if the slave hung up (EIO). */
    private int readAvailable(byte[] buffer, int offset, int length) throws IOException {
        long n;
        try {
            n = (long) READ.invokeExact(readErrno, masterFd, readBuffer,
                    (long) Math.min(length, BUFFER_BYTES));
        } catch (Throwable t) {
            throw new IOException("read failed on " + name() + ": " + t, t);
        }
        if (n < 0) {
            int errno = (int) ERRNO.get(readErrno, 0L);
            if (errno == EINTR || errno == EAGAIN) {
                return 0;
            }
            if (errno == EIO) {
                return -1;
            }
            throw new IOException("read on " + name() + " failed: " + describe(errno));
        }
        MemorySegment.copy(readBuffer, ValueLayout.JAVA_BYTE, 0, buffer, offset, (int) n);
        return (int) n;
    }

    private void ensureOpen() throws IOException {
        if (closed) {
            throw new IOException(name() + " is closed");
        }
    }

    /** Closes the master; the slave then sees a hang-up. Idempotent. */
    @Override
    public synchronized void close() {
        if (closed) {
            return;
        }
        closed = true;
        try (Arena local = Arena.ofConfined()) {
            int ignored = (int) CLOSE.invokeExact(local.allocate(ERRNO_STATE), masterFd);
        } catch (Throwable t) {
            // Closing is best effort; the descriptor is gone with the process anyway.
        }
        // The buffers belong to an automatic arena, freed by the garbage collector once no reader
        // still inside poll() or read() can touch them.
    }

    private static MethodHandle downcall(String function, FunctionDescriptor descriptor) {
        return LINKER.downcallHandle(find(function), descriptor, CAPTURE_ERRNO);
    }

    private static MemorySegment find(String function) {
        return LIBC.find(function).orElseThrow(() -> new UnsupportedOperationException(
                "libc has no " + function + ": pseudo-terminals need Linux"));
    }

    private static void check(String function, int rc, MemorySegment errno) throws IOException {
        if (rc != 0) {
            throw failure(function, errno);
        }
    }

    private static IOException failure(String function, MemorySegment errno) {
        return new IOException(function + " failed: " + describe((int) ERRNO.get(errno, 0L)));
    }

    private static String describe(int errno) {
        try {
            MemorySegment text = (MemorySegment) STRERROR.invokeExact(errno);
            return "errno " + errno + " (" + text.reinterpret(256).getString(0) + ")";
        } catch (Throwable t) {
            return "errno " + errno;
        }
    }
}
