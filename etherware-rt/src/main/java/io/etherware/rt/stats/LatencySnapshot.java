package io.etherware.rt.stats;

import java.util.Locale;
import org.HdrHistogram.Histogram;

/**
 * A read-only distribution of latencies in nanoseconds, as recorded by a {@link LatencyRecorder}
 * up to one moment. Values are kept to the recorder's significant digits: a percentile or the
 * maximum is the highest value of its bucket, within that precision of the samples themselves.
 *
 * <p>Immutable and safe to share between threads. Reading it does not touch the recorder.
 */
public final class LatencySnapshot {

    // Never handed out and never changed after construction: the histogram library stays an
    // implementation detail of this module (no 'requires transitive' on an automatic module).
    private final Histogram histogram;

    LatencySnapshot(Histogram histogram) {
        this.histogram = histogram;
    }

    /**
     * Samples recorded.
     *
     * @return the number of samples, 0 if none
     */
    public long count() {
        return histogram.getTotalCount();
    }

    /**
     * The smallest sample.
     *
     * @return the smallest sample in nanoseconds (to the recorder's precision), 0 if none
     */
    public long minNs() {
        return histogram.getMinValue();
    }

    /**
     * The largest sample.
     *
     * @return the largest sample in nanoseconds (the highest value of its bucket), 0 if none
     */
    public long maxNs() {
        return histogram.getMaxValue();
    }

    /**
     * The mean of the samples.
     *
     * @return the mean in nanoseconds, 0 if none
     */
    public double meanNs() {
        return histogram.getMean();
    }

    /**
     * The value that {@code percentile} percent of the samples are at or below.
     *
     * @param percentile from 0 to 100, e.g. 99.9
     * @return that value in nanoseconds (the highest value of its bucket), 0 if there are no samples
     * @throws IllegalArgumentException if {@code percentile} is outside [0, 100]
     */
    public long percentileNs(double percentile) {
        if (!(percentile >= 0.0 && percentile <= 100.0)) {
            throw new IllegalArgumentException("percentile=" + percentile + ": must be within [0, 100]");
        }
        return histogram.getValueAtPercentile(percentile);
    }

    /**
     * The largest value recorded as itself; larger samples were recorded as this.
     *
     * @return the recorder's highest trackable value in nanoseconds
     */
    public long highestTrackableNs() {
        return histogram.getHighestTrackableValue();
    }

    /**
     * This distribution with {@code count} more samples of {@code valueNs}, e.g. releases that
     * were skipped and should count at a bound. This snapshot does not change.
     *
     * @param valueNs the value to add, clamped to [0, {@link #highestTrackableNs()}]
     * @param count   how many samples of it, 0 or more
     * @return a new snapshot
     * @throws IllegalArgumentException if {@code count} is negative
     */
    public LatencySnapshot withSamples(long valueNs, long count) {
        if (count < 0) {
            throw new IllegalArgumentException("count=" + count + ": must be >= 0");
        }
        Histogram more = histogram.copy();
        if (count > 0) {
            more.recordValueWithCount(Math.clamp(valueNs, 0, more.getHighestTrackableValue()), count);
        }
        return new LatencySnapshot(more);
    }

    /** Equal when both hold the same samples at the same precision. */
    @Override
    public boolean equals(Object other) {
        return other instanceof LatencySnapshot snapshot && histogram.equals(snapshot.histogram);
    }

    @Override
    public int hashCode() {
        return histogram.hashCode();
    }

    /** The count with p50, p99, p99.9 and max in microseconds, for logs and assertion messages. */
    @Override
    public String toString() {
        return String.format(Locale.ROOT, "LatencySnapshot[count=%d, p50=%.1f us, p99=%.1f us, p99.9=%.1f us, max=%.1f us]",
                count(), percentileNs(50) / 1e3, percentileNs(99) / 1e3, percentileNs(99.9) / 1e3, maxNs() / 1e3);
    }
}
