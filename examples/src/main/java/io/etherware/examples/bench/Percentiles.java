package io.etherware.examples.bench;

import io.etherware.rt.stats.LatencySnapshot;
import java.util.function.DoubleToLongFunction;
import org.HdrHistogram.Histogram;

/**
 * The summary of one measured distribution, in nanoseconds: how many samples and the p50, p99,
 * p99.9 and maximum. Immutable.
 *
 * @param count  samples (0: nothing measured)
 * @param p50Ns  median
 * @param p99Ns  99th percentile
 * @param p999Ns 99.9th percentile
 * @param maxNs  largest sample
 */
public record Percentiles(long count, long p50Ns, long p99Ns, long p999Ns, long maxNs) {

    /** No samples. */
    public static final Percentiles NONE = new Percentiles(0, 0, 0, 0, 0);

    /** Rejects negative counts and values out of order. */
    public Percentiles {
        if (count < 0) {
            throw new IllegalArgumentException("count=" + count + ": must be >= 0");
        }
        if (count > 0 && !(p50Ns <= p99Ns && p99Ns <= p999Ns && p999Ns <= maxNs)) {
            throw new IllegalArgumentException("p50Ns=" + p50Ns + ", p99Ns=" + p99Ns + ", p999Ns=" + p999Ns
                    + ", maxNs=" + maxNs + ": percentiles must not decrease");
        }
    }

    /** The percentiles of {@code histogram}, whose values are nanoseconds. */
    public static Percentiles of(Histogram histogram) {
        if (histogram.getTotalCount() == 0) {
            return NONE;
        }
        return clamped(histogram.getTotalCount(), histogram.getMaxValue(), histogram::getValueAtPercentile);
    }

    /** The percentiles of a snapshot from Etherware's statistics (a scheduler's, the Notifier's). */
    public static Percentiles of(LatencySnapshot snapshotNs) {
        if (snapshotNs.count() == 0) {
            return NONE;
        }
        return clamped(snapshotNs.count(), snapshotNs.maxNs(), snapshotNs::percentileNs);
    }

    /**
     * A histogram reports the highest equivalent value of a bucket for percentiles and the exact
     * maximum: clamp each percentile to the next so the summary stays ordered.
     */
    private static Percentiles clamped(long count, long maxNs, DoubleToLongFunction percentileNs) {
        long p999Ns = Math.min(maxNs, percentileNs.applyAsLong(99.9));
        long p99Ns = Math.min(p999Ns, percentileNs.applyAsLong(99));
        long p50Ns = Math.min(p99Ns, percentileNs.applyAsLong(50));
        return new Percentiles(count, p50Ns, p99Ns, p999Ns, maxNs);
    }

    /** The percentiles of samples in nanoseconds (any order). */
    public static Percentiles ofSamples(long[] samplesNs, int count) {
        Histogram histogram = Histograms.latencyNs();
        for (int i = 0; i < count; i++) {
            histogram.recordValue(Histograms.clampNs(samplesNs[i]));
        }
        return of(histogram);
    }
}
