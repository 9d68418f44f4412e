package io.etherware.examples.scenario;

import java.util.Objects;

/**
 * The plant's ground truth as the {@link PlantProbe} sampled it: parallel arrays, one entry per
 * sample, in time order. Owned by whoever holds it; the probe hands out copies.
 *
 * @param timeNs    when each sample was taken, on the node's monotonic clock
 * @param theta1Rad the arm angle θ1
 * @param theta2Rad the pendulum angle θ2 (0 upright)
 * @param torqueNm  the torque the motor applied at that moment (0 after the board's watchdog cut it)
 */
public record ProbeSamples(long[] timeNs, double[] theta1Rad, double[] theta2Rad, double[] torqueNm) {

    public ProbeSamples {
        Objects.requireNonNull(timeNs, "timeNs");
        Objects.requireNonNull(theta1Rad, "theta1Rad");
        Objects.requireNonNull(theta2Rad, "theta2Rad");
        Objects.requireNonNull(torqueNm, "torqueNm");
        int n = timeNs.length;
        if (theta1Rad.length != n || theta2Rad.length != n || torqueNm.length != n) {
            throw new IllegalArgumentException("sample arrays differ in length: timeNs=" + n + ", theta1Rad="
                    + theta1Rad.length + ", theta2Rad=" + theta2Rad.length + ", torqueNm=" + torqueNm.length);
        }
    }

    /** The number of samples. */
    public int size() {
        return timeNs.length;
    }

    /** The largest |θ2|, 0 without samples. */
    public double maxAbsTheta2Rad() {
        double max = 0.0;
        for (double theta2 : theta2Rad) {
            max = Math.max(max, Math.abs(theta2));
        }
        return max;
    }

    /** The root mean square of θ2, 0 without samples. */
    public double rmsTheta2Rad() {
        return rms(theta2Rad);
    }

    /** The root mean square of θ1, 0 without samples. */
    public double rmsTheta1Rad() {
        return rms(theta1Rad);
    }

    private static double rms(double[] values) {
        if (values.length == 0) {
            return 0.0;
        }
        double sum = 0.0;
        for (double value : values) {
            sum += value * value;
        }
        return Math.sqrt(sum / values.length);
    }

    /** The time of the first sample with |θ2| above {@code thresholdRad}, or -1 if none. */
    public long firstTimeAboveNs(double thresholdRad) {
        for (int i = 0; i < theta2Rad.length; i++) {
            if (Math.abs(theta2Rad[i]) > thresholdRad) {
                return timeNs[i];
            }
        }
        return -1L;
    }
}
