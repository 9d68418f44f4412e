package io.etherware.services.time;

/**
 * The clock filter for one peer: keeps the last exchanges in a window, trusts the one with the
 * smallest round trip (its offset error is bounded by the smallest half round trip, as in NTP's
 * clock filter, RFC 5905 Section 10), and, once the well-measured exchanges span long enough,
 * fits a line through them so that the peer's drift is followed between exchanges instead of
 * showing up as a stale offset.
 *
 * <p>Not thread-safe: {@link NetworkTime} serializes calls per peer.
 */
final class OffsetEstimator {

    /** A drift beyond this is not a crystal's; the fit is clamped to it. */
    static final double MAX_DRIFT_PPM = 500;
    /** Exchanges whose round trip is within twice the best plus this slack count as well measured. */
    private static final long GOOD_SLACK_NS = 20_000;

    private final String nodeId;
    private final TimeSample[] window;
    private final long minDriftSpanNs;
    private int count;
    private int next;
    private double driftPpm;

    OffsetEstimator(String nodeId, int windowSize, long minDriftSpanNs) {
        this.nodeId = nodeId;
        this.window = new TimeSample[windowSize];
        this.minDriftSpanNs = minDriftSpanNs;
    }

    /**
     * Adds an exchange and returns the new estimate, or null if the exchange is impossible (a
     * negative round trip: a clock stepped during it) and was ignored.
     */
    PeerTime add(TimeSample sample) {
        if (sample.roundTripNs() < 0 || sample.t4() < sample.t1()) {
            return null;
        }
        window[next] = sample;
        next = (next + 1) % window.length;
        count = Math.min(count + 1, window.length);
        return estimate();
    }

    private PeerTime estimate() {
        TimeSample best = null;
        for (int i = 0; i < count; i++) {
            TimeSample each = window[i];
            if (best == null || each.roundTripNs() < best.roundTripNs()) {
                best = each;
            }
        }
        long limitNs = 2 * best.roundTripNs() + GOOD_SLACK_NS;
        // Least squares of offset over time on the well-measured exchanges, relative to the best
        // one so the sums stay small; double precision is ample for microseconds over minutes.
        int n = 0;
        double sumX = 0;
        double sumY = 0;
        long minX = Long.MAX_VALUE;
        long maxX = Long.MIN_VALUE;
        for (int i = 0; i < count; i++) {
            TimeSample each = window[i];
            if (each.roundTripNs() <= limitNs) {
                long x = each.localMidpointNs() - best.localMidpointNs();
                n++;
                sumX += x;
                sumY += each.offsetNs() - best.offsetNs();
                minX = Math.min(minX, x);
                maxX = Math.max(maxX, x);
            }
        }
        long offsetNs = best.offsetNs();
        if (n >= 3 && maxX - minX >= minDriftSpanNs) {
            double meanX = sumX / n;
            double meanY = sumY / n;
            double sxy = 0;
            double sxx = 0;
            for (int i = 0; i < count; i++) {
                TimeSample each = window[i];
                if (each.roundTripNs() <= limitNs) {
                    double dx = (each.localMidpointNs() - best.localMidpointNs()) - meanX;
                    sxy += dx * ((each.offsetNs() - best.offsetNs()) - meanY);
                    sxx += dx * dx;
                }
            }
            double slope = Math.clamp(sxy / sxx, -MAX_DRIFT_PPM * 1e-6, MAX_DRIFT_PPM * 1e-6);
            driftPpm = slope * 1e6;
            // The fitted line at the best exchange's time: averages the good exchanges' errors.
            offsetNs += Math.round(meanY - slope * meanX);
        }
        return new PeerTime(nodeId, offsetNs, best.localMidpointNs(), driftPpm, best.roundTripNs(),
                best.roundTripNs() / 2, count);
    }
}
