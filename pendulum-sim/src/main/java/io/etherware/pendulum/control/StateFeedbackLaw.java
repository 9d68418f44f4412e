package io.etherware.pendulum.control;

import java.util.Objects;

/**
 * The control law of the paper's Section VI-A, {@code u = −K (x − x0)} with
 * {@code x0 = [θ1r, 0, 0, 0]}, saturated to the motor's torque range.
 *
 * <p>θ2 is wrapped to (−π, π] so a pendulum that has turned over a whole revolution counts as
 * upright again; θ1 is not wrapped, so the arm unwinds back to θ1r (cables stay untwisted).
 * Immutable; thread-safe; allocation-free.
 */
public final class StateFeedbackLaw {

    private final GainSet gains;
    private final double theta1ReferenceRad;
    private final double maxTorqueNm;

    /**
     * A law.
     *
     * @param gains the gain K
     * @param theta1ReferenceRad θ1r, the arm set point
     * @param maxTorqueNm the saturation limit, > 0
     */
    public StateFeedbackLaw(GainSet gains, double theta1ReferenceRad, double maxTorqueNm) {
        this.gains = Objects.requireNonNull(gains, "gains");
        if (!Double.isFinite(theta1ReferenceRad)) {
            throw new IllegalArgumentException("theta1ReferenceRad=" + theta1ReferenceRad
                    + ": must be finite");
        }
        if (!(maxTorqueNm > 0) || !Double.isFinite(maxTorqueNm)) {
            throw new IllegalArgumentException("maxTorqueNm=" + maxTorqueNm + ": must be finite and > 0");
        }
        this.theta1ReferenceRad = theta1ReferenceRad;
        this.maxTorqueNm = maxTorqueNm;
    }

    /** {@code −K (x − x0)} before saturation. */
    public double unsaturatedTorqueNm(double theta1Rad, double theta1RateRadPerS, double theta2Rad,
            double theta2RateRadPerS) {
        return -(gains.kTheta1NmPerRad() * (theta1Rad - theta1ReferenceRad)
                + gains.kTheta1RateNmsPerRad() * theta1RateRadPerS
                + gains.kTheta2NmPerRad() * wrapToPi(theta2Rad)
                + gains.kTheta2RateNmsPerRad() * theta2RateRadPerS);
    }

    /** {@code u = −K (x − x0)}, clamped to ±{@link #maxTorqueNm()}. */
    public double torqueNm(double theta1Rad, double theta1RateRadPerS, double theta2Rad,
            double theta2RateRadPerS) {
        return clamp(unsaturatedTorqueNm(theta1Rad, theta1RateRadPerS, theta2Rad,
                theta2RateRadPerS), maxTorqueNm);
    }

    /** {@code value} clamped to ±limit; NaN becomes 0 (never command a NaN torque). */
    public static double clamp(double value, double limit) {
        if (Double.isNaN(value)) {
            return 0.0;
        }
        return Math.max(-limit, Math.min(limit, value));
    }

    /** An angle wrapped to (−π, π]. */
    public static double wrapToPi(double angleRad) {
        double wrapped = Math.IEEEremainder(angleRad, 2.0 * Math.PI);
        return wrapped == -Math.PI ? Math.PI : wrapped;
    }

    /** The gain. */
    public GainSet gains() {
        return gains;
    }

    /** θ1r. */
    public double theta1ReferenceRad() {
        return theta1ReferenceRad;
    }

    /** The saturation limit. */
    public double maxTorqueNm() {
        return maxTorqueNm;
    }
}
