package io.etherware.pendulum.components;

import java.util.ArrayList;
import java.util.Arrays;
import java.util.List;

/**
 * A {@link ControlListener} that keeps the first {@code capacity} cycles in memory, for plotting
 * after a run (15 ms cycles: 4000 per minute). Cycles past the capacity are counted, not kept.
 *
 * <p>Thread-safe: the controller appends on its dispatcher while another thread reads; the append
 * takes an uncontended monitor for a few nanoseconds and never allocates.
 */
public final class ControlRecorder implements ControlListener {

    private final ControlCycle[] cycles;
    private int size;
    private long dropped;

    /** A recorder keeping up to {@code capacity} cycles. */
    public ControlRecorder(int capacity) {
        if (capacity <= 0) {
            throw new IllegalArgumentException("capacity=" + capacity + ": must be > 0");
        }
        this.cycles = new ControlCycle[capacity];
    }

    @Override
    public synchronized void onCycle(ControlCycle cycle) {
        if (size < cycles.length) {
            cycles[size++] = cycle;
        } else {
            dropped++;
        }
    }

    /** The cycles recorded so far, in order. */
    public synchronized List<ControlCycle> cycles() {
        return new ArrayList<>(Arrays.asList(cycles).subList(0, size));
    }

    /** The number of cycles recorded. */
    public synchronized int size() {
        return size;
    }

    /** Cycles not kept because the recorder was full. */
    public synchronized long dropped() {
        return dropped;
    }
}
