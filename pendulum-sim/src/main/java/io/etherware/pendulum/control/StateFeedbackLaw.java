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
     * @throws NullPointerException     when {@code gains} is null
     * @throws IllegalArgumentException when {@code theta1ReferenceRad} is not finite or
     *                                  {@code maxTorqueNm} is not finite and positive
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

    /**
     * {@code −K (x − x0)} before saturation, with θ2 wrapped to (−π, π].
     *
     * @param theta1Rad         θ1, the arm angle, in rad (not wrapped)
     * @param theta1RateRadPerS θ̇1, in rad/s
     * @param theta2Rad         θ2, the pendulum angle, in rad, 0 upright
     * @param theta2RateRadPerS θ̇2, in rad/s
     * @return the torque, in N·m; NaN when an input is
     */
    public double unsaturatedTorqueNm(double theta1Rad, double theta1RateRadPerS, double theta2Rad,
            double theta2RateRadPerS) {
        return -(gains.kTheta1NmPerRad() * (theta1Rad - theta1ReferenceRad)
                + gains.kTheta1RateNmsPerRad() * theta1RateRadPerS
                + gains.kTheta2NmPerRad() * wrapToPi(theta2Rad)
                + gains.kTheta2RateNmsPerRad() * theta2RateRadPerS);
    }

    /**
     * {@code u = −K (x − x0)}, clamped to ±{@link #maxTorqueNm()}.
     *
     * @param theta1Rad         θ1, the arm angle, in rad (not wrapped)
     * @param theta1RateRadPerS θ̇1, in rad/s
     * @param theta2Rad         θ2, the pendulum angle, in rad, 0 upright
     * @param theta2RateRadPerS θ̇2, in rad/s
     * @return the torque to command, in N·m; 0 when the law gives NaN
     */
    public double torqueNm(double theta1Rad, double theta1RateRadPerS, double theta2Rad,
            double theta2RateRadPerS) {
        return clamp(unsaturatedTorqueNm(theta1Rad, theta1RateRadPerS, theta2Rad,
                theta2RateRadPerS), maxTorqueNm);
    }

    /**
     * A value clamped to a symmetric range; NaN becomes 0 (never command a NaN torque).
     *
     * @param value the value
     * @param limit the bound of the range, 0 or more
     * @return {@code value} within [−limit, limit]
     */
    public static double clamp(double value, double limit) {
        if (Double.isNaN(value)) {
            return 0.0;
        }
        return Math.max(-limit, Math.min(limit, value));
    }

    /**
     * An angle wrapped to (−π, π].
     *
     * @param angleRad an angle, in rad
     * @return the same direction, in (−π, π]
     */
    public static double wrapToPi(double angleRad) {
        double wrapped = Math.IEEEremainder(angleRad, 2.0 * Math.PI);
        return wrapped == -Math.PI ? Math.PI : wrapped;
    }

    /**
     * The gain.
     *
     * @return the gain set K
     */
    public GainSet gains() {
        return gains;
    }

    /**
     * θ1r, the arm set point.
     *
     * @return the set point, in rad
     */
    public double theta1ReferenceRad() {
        return theta1ReferenceRad;
    }

    /**
     * The saturation limit.
     *
     * @return the limit, in N·m, positive
     */
    public double maxTorqueNm() {
        return maxTorqueNm;
    }
}
