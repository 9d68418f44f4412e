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

    /**
     * A recorder keeping up to {@code capacity} cycles, allocated up front.
     *
     * @param capacity how many cycles to keep, greater than 0 (15 ms cycles: 4000 per minute)
     * @throws IllegalArgumentException when {@code capacity} is not positive
     */
    public ControlRecorder(int capacity) {
        if (capacity <= 0) {
            throw new IllegalArgumentException("capacity=" + capacity + ": must be > 0");
        }
        this.cycles = new ControlCycle[capacity];
    }

    /**
     * Keeps the cycle, or counts it as dropped when full; allocation-free.
     *
     * @param cycle the cycle that ended
     */
    @Override
    public synchronized void onCycle(ControlCycle cycle) {
        if (size < cycles.length) {
            cycles[size++] = cycle;
        } else {
            dropped++;
        }
    }

    /**
     * The cycles recorded so far, in order.
     *
     * @return a new list the caller owns
     */
    public synchronized List<ControlCycle> cycles() {
        return new ArrayList<>(Arrays.asList(cycles).subList(0, size));
    }

    /**
     * The number of cycles recorded.
     *
     * @return the count, at most the capacity
     */
    public synchronized int size() {
        return size;
    }

    /**
     * Cycles not kept because the recorder was full.
     *
     * @return the count
     */
    public synchronized long dropped() {
        return dropped;
    }
}
