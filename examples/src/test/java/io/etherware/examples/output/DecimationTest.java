package io.etherware.examples.output;

import static org.junit.jupiter.api.Assertions.assertArrayEquals;
import static org.junit.jupiter.api.Assertions.assertEquals;
import static org.junit.jupiter.api.Assertions.assertTrue;

import java.util.Random;
import org.junit.jupiter.api.Test;

class DecimationTest {

    @Test
    void shouldKeepEveryColumnsSmallestAndLargestInTheirOrderAndNothingElse() {
        // Powers of two, so that the columns' edges fall exactly on samples.
        int n = 4_096;
        int columns = 128;
        double[] x = new double[n];
        double[] y = new double[n];
        var random = new Random(1);
        for (int i = 0; i < n; i++) {
            x[i] = i;
            y[i] = random.nextGaussian();
        }
        y[1234] = 50.0; // one spike, as a late Tick is
        y[2345] = -50.0;

        Decimation.Series thin = Decimation.minMaxPerColumn(x, y, 0.0, n, columns);

        assertTrue(thin.size() <= 2 * columns, thin.size() + " points");
        double perColumn = n / (double) columns;
        for (int c = 0; c < columns; c++) {
            double min = Double.MAX_VALUE;
            double max = -Double.MAX_VALUE;
            for (int i = (int) (c * perColumn); i < (int) ((c + 1) * perColumn); i++) {
                min = Math.min(min, y[i]);
                max = Math.max(max, y[i]);
            }
            double keptMin = Double.MAX_VALUE;
            double keptMax = -Double.MAX_VALUE;
            for (int k = 0; k < thin.size(); k++) {
                if ((int) thin.x()[k] / (n / columns) == c) {
                    keptMin = Math.min(keptMin, thin.y()[k]);
                    keptMax = Math.max(keptMax, thin.y()[k]);
                }
            }
            assertEquals(min, keptMin, "column " + c);
            assertEquals(max, keptMax, "column " + c);
        }
        for (int k = 1; k < thin.size(); k++) {
            assertTrue(thin.x()[k] > thin.x()[k - 1], "in time order at " + k);
        }
    }

    @Test
    void shouldKeepAShortSeriesWholeAndAGapAsOneBreak() {
        double[] x = {0, 1, 2, 3, 4, 5};
        double[] y = {1, 2, Double.NaN, Double.NaN, 5, 6};

        Decimation.Series thin = Decimation.minMaxPerColumn(x, y, 0, 6, 600);

        assertArrayEquals(new double[] {0, 1, 2, 4, 5}, thin.x());
        assertArrayEquals(new double[] {1, 2, Double.NaN, 5, 6}, thin.y());
    }
}
