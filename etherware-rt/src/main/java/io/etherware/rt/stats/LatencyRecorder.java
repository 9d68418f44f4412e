package io.etherware.rt.stats;

import org.HdrHistogram.Histogram;
import org.HdrHistogram.SingleWriterRecorder;

/**
 * Records latencies in nanoseconds and gives readers a {@link LatencySnapshot} of everything
 * recorded since it was made.
 *
 * <p>Threading: {@link #record} is for one writer thread at a time (a dispatcher's, the
 * Notifier's): wait-free, no locks, no allocation, so it is fit for a per-job path.
 * {@link #snapshot()} may be called from any thread; snapshots are serialized here and each one
 * copies the distribution, so reading is for monitoring, not for a per-message path.
 */
public final class LatencyRecorder {

    private final SingleWriterRecorder recorder;
    private final long highestTrackableNs;

    // Reader side, guarded by this.
    private final Histogram total;
    // A recycled interval histogram must come from the recorder it goes back to.
    private Histogram interval;

    /**
     * A recorder from 1 ns to {@code highestTrackableNs} at {@code significantDigits} decimal
     * digits of precision (2: values within 1 %).
     *
     * @param highestTrackableNs the largest value kept as itself; larger samples count as this
     * @param significantDigits  precision of every recorded value, 0 to 5
     * @throws IllegalArgumentException if either is out of range
     */
    public LatencyRecorder(long highestTrackableNs, int significantDigits) {
        if (highestTrackableNs < 2) {
            throw new IllegalArgumentException("highestTrackableNs=" + highestTrackableNs + ": must be >= 2");
        }
        if (significantDigits < 0 || significantDigits > 5) {
            throw new IllegalArgumentException("significantDigits=" + significantDigits + ": must be within [0, 5]");
        }
        this.highestTrackableNs = highestTrackableNs;
        this.recorder = new SingleWriterRecorder(1, highestTrackableNs, significantDigits);
        this.total = new Histogram(1, highestTrackableNs, significantDigits);
    }

    /**
     * Records one sample. Writer thread only.
     *
     * @param latencyNs the sample; negative counts as 0, above the highest trackable value as that
     */
    public void record(long latencyNs) {
        recorder.recordValue(Math.clamp(latencyNs, 0, highestTrackableNs));
    }

    /**
     * Everything recorded since this recorder was made. Any thread.
     *
     * @return a snapshot the caller owns
     */
    public synchronized LatencySnapshot snapshot() {
        interval = recorder.getIntervalHistogram(interval);
        total.add(interval);
        return new LatencySnapshot(total.copy());
    }

    /**
     * The largest value kept as itself.
     *
     * @return the highest trackable value in nanoseconds
     */
    public long highestTrackableNs() {
        return highestTrackableNs;
    }
}
