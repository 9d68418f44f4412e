package io.etherware.examples.bench;

import java.io.FileOutputStream;
import java.io.IOException;

/**
 * Holds {@code /dev/cpu_dma_latency} at 0 µs while open, as {@code cyclictest} does for itself:
 * the CPUs then stay out of their deep idle states, whose wake-up (~100 µs on the development VM)
 * would otherwise dominate every row that waits for a thread to wake. The bench holds it for the
 * whole run, so every row, baselines included, runs in the same CPU-latency state, and the report
 * says which. Closing the file releases the request (the kernel's PM QoS interface).
 */
final class CpuLatencyHold implements AutoCloseable {

    private static final String DEVICE = "/dev/cpu_dma_latency";

    private final FileOutputStream device;
    private final String state;

    private CpuLatencyHold(FileOutputStream device, String state) {
        this.device = device;
        this.state = state;
    }

    /** Requests 0 µs; where that is refused, holds nothing and says why. */
    static CpuLatencyHold request() {
        try {
            var device = new FileOutputStream(DEVICE);
            device.write(new byte[] {0, 0, 0, 0}); // a 32-bit 0, in any byte order
            device.flush();
            return new CpuLatencyHold(device, DEVICE + " held at 0 us (CPUs kept awake, as cyclictest does)");
        } catch (IOException | SecurityException e) {
            return new CpuLatencyHold(null, DEVICE + " not held (" + e.getMessage() + "): CPUs may sleep deeply");
        }
    }

    /** Not requested: the CPUs idle as the OS likes. */
    static CpuLatencyHold none() {
        return new CpuLatencyHold(null, DEVICE + " not held (--cpus-may-sleep): CPUs may sleep deeply");
    }

    boolean isHeld() {
        return device != null;
    }

    /** One line for the report. */
    String state() {
        return state;
    }

    @Override
    public void close() {
        if (device != null) {
            try {
                device.close();
            } catch (IOException e) {
                // Released with the file either way.
            }
        }
    }
}
