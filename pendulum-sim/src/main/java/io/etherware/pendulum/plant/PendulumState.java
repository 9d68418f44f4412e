package io.etherware.pendulum.plant;

/**
 * A state of the pendulum, in the paper's order {@code x = [θ1, θ̇1, θ2, θ̇2]}; {@code θ2 = 0} is
 * upright. Immutable value; thread-safe.
 *
 * @param theta1Rad arm angle θ1 (multi-turn, not wrapped)
 * @param theta1RateRadPerS arm rate θ̇1
 * @param theta2Rad pendulum angle θ2, 0 upright
 * @param theta2RateRadPerS pendulum rate θ̇2
 */
public record PendulumState(
        double theta1Rad, double theta1RateRadPerS, double theta2Rad, double theta2RateRadPerS) {

    /** Index of θ1 in the state vector. */
    public static final int THETA1 = 0;
    /** Index of θ̇1 in the state vector. */
    public static final int THETA1_RATE = 1;
    /** Index of θ2 in the state vector. */
    public static final int THETA2 = 2;
    /** Index of θ̇2 in the state vector. */
    public static final int THETA2_RATE = 3;
    /** Length of the state vector. */
    public static final int SIZE = 4;

    /** At rest, upright, with the arm at {@code theta1Rad}. */
    public static PendulumState upright(double theta1Rad) {
        return new PendulumState(theta1Rad, 0.0, 0.0, 0.0);
    }

    /** From a state vector {@code [θ1, θ̇1, θ2, θ̇2]}. */
    public static PendulumState of(double[] x) {
        if (x.length != SIZE) {
            throw new IllegalArgumentException("state vector length=" + x.length + ": must be " + SIZE);
        }
        return new PendulumState(x[THETA1], x[THETA1_RATE], x[THETA2], x[THETA2_RATE]);
    }

    /** The state vector {@code [θ1, θ̇1, θ2, θ̇2]}. */
    public double[] toArray() {
        return new double[] {theta1Rad, theta1RateRadPerS, theta2Rad, theta2RateRadPerS};
    }

    /** Copies the state vector into {@code out}, without allocating. */
    public void copyInto(double[] out) {
        out[THETA1] = theta1Rad;
        out[THETA1_RATE] = theta1RateRadPerS;
        out[THETA2] = theta2Rad;
        out[THETA2_RATE] = theta2RateRadPerS;
    }
}
