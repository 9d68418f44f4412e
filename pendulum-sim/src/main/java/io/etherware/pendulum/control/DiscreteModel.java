package io.etherware.pendulum.control;

import io.etherware.pendulum.linalg.Matrices;
import io.etherware.pendulum.linalg.MatrixExponential;
import io.etherware.pendulum.plant.LinearModel;

/**
 * The exact zero-order-hold discretization of {@code ẋ = A x + B u} at a sample period T, with
 * an optional input delay d (0 ≤ d ≤ T) from sampling to the torque taking effect:
 *
 * <pre>
 * x[k+1] = Φ x[k] + Γ0 u[k] + Γ1 u[k-1]
 * Φ  = e^{AT}
 * Γ0 = ∫₀^{T-d} e^{As} ds B          (u[k] acts over [kT+d, (k+1)T])
 * Γ1 = e^{A(T-d)} ∫₀^{d} e^{As} ds B  (u[k-1] still acts over [kT, kT+d])
 * </pre>
 *
 * The integrals come from one matrix exponential of the augmented matrix {@code [[A, B], [0, 0]]}
 * (Van Loan's method). Immutable: accessors return copies. Thread-safe.
 */
public final class DiscreteModel {

    private final double[][] phi;
    private final double[][] gammaNow;
    private final double[][] gammaPrevious;
    private final long periodNs;
    private final long delayNs;

    private DiscreteModel(double[][] phi, double[][] gammaNow, double[][] gammaPrevious,
            long periodNs, long delayNs) {
        this.phi = phi;
        this.gammaNow = gammaNow;
        this.gammaPrevious = gammaPrevious;
        this.periodNs = periodNs;
        this.delayNs = delayNs;
    }

    /**
     * ZOH discretization at a sample period, no input delay.
     *
     * @param model    the continuous-time model
     * @param periodNs the sample period T, in nanoseconds, greater than 0
     * @return the discrete model, with Γ1 = 0
     * @throws IllegalArgumentException when {@code periodNs} is not positive
     */
    public static DiscreteModel zeroOrderHold(LinearModel model, long periodNs) {
        return zeroOrderHold(model, periodNs, 0L);
    }

    /**
     * ZOH discretization at a sample period, with the input taking effect some time after the
     * sample.
     *
     * @param model    the continuous-time model
     * @param periodNs the sample period T, in nanoseconds, greater than 0
     * @param delayNs  the input delay d, in nanoseconds, within [0, periodNs]
     * @return the discrete model
     * @throws IllegalArgumentException when {@code periodNs} or {@code delayNs} is out of range
     */
    public static DiscreteModel zeroOrderHold(LinearModel model, long periodNs, long delayNs) {
        if (periodNs <= 0) {
            throw new IllegalArgumentException("periodNs=" + periodNs + ": must be > 0");
        }
        if (delayNs < 0 || delayNs > periodNs) {
            throw new IllegalArgumentException("delayNs=" + delayNs + ": must be within [0, periodNs="
                    + periodNs + "]");
        }
        double[][] a = model.a();
        double[][] b = model.b();
        double periodS = periodNs * 1e-9;
        double delayS = delayNs * 1e-9;
        double[][][] afterDelay = transitionAndInput(a, b, periodS - delayS);
        double[][][] duringDelay = transitionAndInput(a, b, delayS);
        double[][] phi = Matrices.multiply(afterDelay[0], duringDelay[0]);
        double[][] gammaPrevious = Matrices.multiply(afterDelay[0], duringDelay[1]);
        return new DiscreteModel(phi, afterDelay[1], gammaPrevious, periodNs, delayNs);
    }

    /** {e^{A t}, ∫₀^t e^{As} ds B} from the exponential of {@code [[A, B], [0, 0]] t}. */
    private static double[][][] transitionAndInput(double[][] a, double[][] b, double tS) {
        int n = a.length;
        double[][] augmented = new double[n + 1][n + 1];
        for (int i = 0; i < n; i++) {
            for (int j = 0; j < n; j++) {
                augmented[i][j] = a[i][j] * tS;
            }
            augmented[i][n] = b[i][0] * tS;
        }
        double[][] exp = MatrixExponential.exp(augmented);
        double[][] transition = new double[n][n];
        double[][] input = new double[n][1];
        for (int i = 0; i < n; i++) {
            System.arraycopy(exp[i], 0, transition[i], 0, n);
            input[i][0] = exp[i][n];
        }
        return new double[][][] {transition, input};
    }

    /**
     * The state transition matrix.
     *
     * @return a copy of Φ = e^{AT}, n×n
     */
    public double[][] phi() {
        return Matrices.copy(phi);
    }

    /**
     * Γ0, the input matrix of the current sample's command.
     *
     * @return a copy of Γ0, n×1
     */
    public double[][] gammaNow() {
        return Matrices.copy(gammaNow);
    }

    /**
     * Γ1, the input matrix of the previous command.
     *
     * @return a copy of Γ1, n×1; zero without delay
     */
    public double[][] gammaPrevious() {
        return Matrices.copy(gammaPrevious);
    }

    /**
     * The input matrix the plain ZOH model would have.
     *
     * @return Γ = Γ0 + Γ1, a new n×1 matrix
     */
    public double[][] gamma() {
        return Matrices.add(gammaNow, gammaPrevious);
    }

    /**
     * The sample period T.
     *
     * @return the period, in nanoseconds
     */
    public long periodNs() {
        return periodNs;
    }

    /**
     * The input delay d.
     *
     * @return the delay, in nanoseconds, within [0, {@link #periodNs()}]
     */
    public long delayNs() {
        return delayNs;
    }
}
