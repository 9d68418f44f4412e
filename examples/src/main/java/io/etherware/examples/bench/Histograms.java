package io.etherware.examples.bench;

import java.util.concurrent.TimeUnit;
import org.HdrHistogram.Histogram;
import org.HdrHistogram.Recorder;

/** The bench's histogram settings in one place: nanoseconds up to 60 s, three significant digits. */
final class Histograms {

    /** Largest value recorded; larger samples are clamped to it. */
    static final long MAX_NS = TimeUnit.SECONDS.toNanos(60);
    private static final int DIGITS = 3;

    private Histograms() {
    }

    static Histogram latencyNs() {
        return new Histogram(MAX_NS, DIGITS);
    }

    /** A recorder for samples taken on other threads (wait-free writers, one reader). */
    static Recorder recorderNs() {
        return new Recorder(MAX_NS, DIGITS);
    }

    static long clampNs(long valueNs) {
        return Math.clamp(valueNs, 0, MAX_NS);
    }
}
