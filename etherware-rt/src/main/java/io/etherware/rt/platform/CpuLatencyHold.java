package io.etherware.rt.platform;

import io.etherware.rt.platform.internal.Errno;
import io.etherware.rt.platform.internal.RefusalWarnings;
import java.io.IOException;
import java.io.OutputStream;
import java.nio.file.AccessDeniedException;
import java.nio.file.Files;
import java.nio.file.NoSuchFileException;
import java.nio.file.Path;
import java.nio.file.StandardOpenOption;
import java.util.Optional;
import java.util.concurrent.atomic.AtomicBoolean;
import org.slf4j.LoggerFactory;

/**
 * Holds {@code /dev/cpu_dma_latency} at 0 µs while open, as {@code cyclictest} does for itself: the
 * kernel then keeps every CPU out of the idle states it cannot leave at once, whose wake-up (about
 * 100 µs on the development VM) would otherwise come on top of every wake-up of a real-time thread.
 * With it held the idle Notifier's p99 lateness fell from 502 µs (releases skipped) to 76 µs in one
 * bench run. The price is power: idle CPUs poll instead of sleeping.
 *
 * <p>The request lasts as long as the file stays open (the kernel's PM QoS interface) and ends with
 * {@link #close()} or the process; several holds, in one process or many, are combined by the kernel
 * (the lowest wins). A refusal (no permission) never throws: it is warned once, with the fix, and
 * the hold holds nothing. A kernel without the device (not Linux, some containers) is not a refusal:
 * there is nothing to hold, which is logged once at INFO.
 *
 * <p>Thread-safety: thread-safe.
 */
public final class CpuLatencyHold implements AutoCloseable {

    /** The device file. */
    public static final String DEVICE = "/dev/cpu_dma_latency";

    private static final AtomicBoolean ABSENCE_LOGGED = new AtomicBoolean();

    private final OutputStream device;
    private final Optional<PlatformRefusal> refusal;
    private final boolean absent;

    private CpuLatencyHold(OutputStream device, Optional<PlatformRefusal> refusal, boolean absent) {
        this.device = device;
        this.refusal = refusal;
        this.absent = absent;
    }

    /**
     * Requests 0 µs by opening {@value #DEVICE} and writing 0. Never throws: where that is refused,
     * the hold holds nothing, warns once per kind and says why in {@link #refusal}; where the device
     * is missing, it holds nothing and says so in {@link #state}. Call it at start, not per message.
     *
     * @return the hold; {@link #close()} it to release the request
     */
    public static CpuLatencyHold request() {
        try {
            // WRITE without CREATE: where the device is missing, never make a file of that name.
            OutputStream device = Files.newOutputStream(Path.of(DEVICE), StandardOpenOption.WRITE);
            try {
                device.write(new byte[] {0, 0, 0, 0}); // a 32-bit 0, in either byte order
                device.flush();
            } catch (IOException e) {
                device.close();
                throw e;
            }
            return new CpuLatencyHold(device, Optional.empty(), false);
        } catch (NoSuchFileException | UnsupportedOperationException e) {
            if (ABSENCE_LOGGED.compareAndSet(false, true)) {
                LoggerFactory.getLogger(CpuLatencyHold.class).info("cpu latency: no {} on this system; nothing to hold",
                        DEVICE);
            }
            return new CpuLatencyHold(null, Optional.empty(), true);
        } catch (IOException | SecurityException e) {
            PlatformRefusal refusal = refusal(e);
            RefusalWarnings.shared().warnOnce(refusal);
            return new CpuLatencyHold(null, Optional.of(refusal), false);
        }
    }

    /**
     * A hold that holds nothing, for when no request is wanted: the CPUs idle as the OS likes.
     *
     * @return a new empty hold, whose {@link #close()} does nothing
     */
    public static CpuLatencyHold none() {
        return new CpuLatencyHold(null, Optional.empty(), false);
    }

    /**
     * Whether the request is in force.
     *
     * @return true when the device was opened and written; {@link #close()} does not reset it
     */
    public boolean isHeld() {
        return device != null;
    }

    /**
     * Why the request was refused.
     *
     * @return the refusal; empty when held, not requested, or the device is missing
     */
    public Optional<PlatformRefusal> refusal() {
        return refusal;
    }

    /**
     * This hold's state for reports.
     *
     * @return one line: held, refused and why, no device, or not requested
     */
    public String state() {
        if (device != null) {
            return "cpu latency: " + DEVICE + " held at 0 us (CPUs kept out of deep idle states, as cyclictest does)";
        }
        if (absent) {
            return "cpu latency: no " + DEVICE + " on this system, nothing held";
        }
        return refusal.map(r -> "cpu latency: " + r + "; CPUs may sleep deeply")
                .orElse("cpu latency: not requested; CPUs may sleep deeply");
    }

    /** Releases the request. Idempotent. */
    @Override
    public void close() {
        if (device != null) {
            try {
                device.close();
            } catch (IOException e) {
                // Released with the file descriptor either way.
            }
        }
    }

    private static PlatformRefusal refusal(Exception e) {
        String message = String.valueOf(e.getMessage());
        int errno = e instanceof SecurityException || e instanceof AccessDeniedException ? Errno.EACCES : Errno.EIO;
        String fix = errno == Errno.EACCES
                ? "run as root, or let the node's user write " + DEVICE + " (e.g. a udev rule giving it group write)"
                : "check " + DEVICE + " (" + message + ")";
        return new PlatformRefusal("cpu latency", DEVICE + "=0us", errno, Errno.name(errno), fix);
    }
}
