package io.etherware.examples.output;

import java.util.Arrays;

/**
 * Thins a time series for drawing without changing what the drawing shows: per pixel column, the
 * smallest and the largest value, in the order they came. A line through those points covers, in
 * every column, exactly the span the full series covers, so no spike or extreme is lost; the
 * points between them would only be drawn over it. A 60 s run at 15 ms (4,000 samples) keeps
 * at most two points per column of an 800 px plot.
 *
 * <p>Stateless and thread-safe.
 */
final class Decimation {

    /** A thinned series: parallel arrays, in the original order. */
    record Series(double[] x, double[] y) {
        int size() {
            return x.length;
        }
    }

    private Decimation() {
    }

    /**
     * {@code x} and {@code y} (x ascending) thinned to at most two points per column, {@code columns}
     * columns spanning {@code x0} to {@code x1}; points beyond them count to the first or last column.
     * A NaN in {@code y} is kept, once, as the break in the line it is.
     */
    static Series minMaxPerColumn(double[] x, double[] y, double x0, double x1, int columns) {
        if (x.length != y.length) {
            throw new IllegalArgumentException("x.length=" + x.length + " differs from y.length=" + y.length);
        }
        if (columns < 1 || !(x1 > x0)) {
            throw new IllegalArgumentException("columns=" + columns + ", x0=" + x0 + ", x1=" + x1
                    + ": need at least one column over a span x1 > x0");
        }
        // Every point kept is a distinct input point, so the input's length bounds the output's.
        double[] outX = new double[x.length];
        double[] outY = new double[y.length];
        int n = 0;
        int column = -1;
        int minAt = -1;
        int maxAt = -1;
        double perColumn = columns / (x1 - x0);
        for (int i = 0; i < x.length; i++) {
            if (Double.isNaN(y[i])) {
                n = flush(x, y, minAt, maxAt, outX, outY, n);
                if (n == 0 || !Double.isNaN(outY[n - 1])) {
                    outX[n] = x[i];
                    outY[n++] = Double.NaN;
                }
                column = -1;
                minAt = -1;
                maxAt = -1;
                continue;
            }
            int at = (int) Math.clamp(Math.floor((x[i] - x0) * perColumn), 0, columns - 1);
            if (at != column) {
                n = flush(x, y, minAt, maxAt, outX, outY, n);
                column = at;
                minAt = i;
                maxAt = i;
            } else if (y[i] < y[minAt]) {
                minAt = i;
            } else if (y[i] > y[maxAt]) {
                maxAt = i;
            }
        }
        n = flush(x, y, minAt, maxAt, outX, outY, n);
        return new Series(Arrays.copyOf(outX, n), Arrays.copyOf(outY, n));
    }

    /** Appends a column's extremes, the earlier first; returns the new count. */
    private static int flush(double[] x, double[] y, int minAt, int maxAt, double[] outX, double[] outY, int n) {
        if (minAt < 0) {
            return n;
        }
        int first = Math.min(minAt, maxAt);
        int last = Math.max(minAt, maxAt);
        outX[n] = x[first];
        outY[n++] = y[first];
        if (last != first) {
            outX[n] = x[last];
            outY[n++] = y[last];
        }
        return n;
    }
}
