package io.etherware.pendulum.control;

import io.etherware.pendulum.linalg.Complex;
import io.etherware.pendulum.linalg.Eigenvalues;
import io.etherware.pendulum.linalg.Matrices;
import io.etherware.pendulum.plant.LinearModel;
import io.etherware.pendulum.plant.PendulumState;
import java.util.List;

/**
 * The discrete closed-loop eigenvalues of the linearized pendulum under a {@link GainSet}, as the
 * loop really runs at a control period T.
 *
 * <ul>
 *   <li>{@link #ideal}: ZOH plant with the true state fed back, {@code eig(Φ − Γ K)}.
 *   <li>{@link #asImplemented}: ZOH plant; only the two angles are measured; the rates come from
 *       {@link VelocityEstimator}'s filtered differences; the torque takes effect {@code delayNs}
 *       after the encoders were sampled (serial transfer, computation, board cycle). The state is
 *       {@code [x, θ[k-1], v[k-1], u[k-1]]}: 9 eigenvalues.
 * </ul>
 *
 * Stateless and thread-safe; design-time only.
 */
public final class LoopAnalysis {

    private LoopAnalysis() {}

    /**
     * Eigenvalues of {@code Φ − Γ K} at a control period, by decreasing modulus.
     *
     * @param model    the continuous-time linear model
     * @param gains    the gain K
     * @param periodNs the control period T, in nanoseconds, greater than 0
     * @return the 4 discrete-time closed-loop eigenvalues
     * @throws IllegalArgumentException when {@code periodNs} is not positive
     */
    public static List<Complex> ideal(LinearModel model, GainSet gains, long periodNs) {
        DiscreteModel discrete = DiscreteModel.zeroOrderHold(model, periodNs);
        double[][] k = {gains.gains()};
        double[][] closed = Matrices.subtract(discrete.phi(),
                Matrices.multiply(discrete.gamma(), k));
        return Eigenvalues.of(closed);
    }

    /**
     * Eigenvalues of the loop with the velocity estimator and an input delay, by decreasing
     * modulus.
     *
     * @param model the continuous-time linear model
     * @param gains the gain K
     * @param periodNs the control period T, in nanoseconds, greater than 0
     * @param delayNs from encoder sampling to the torque taking effect, within [0, periodNs]
     * @param filterTimeConstantNs the estimator's first-order filter constant (0: raw differences)
     * @return the 9 discrete-time closed-loop eigenvalues
     * @throws IllegalArgumentException when {@code periodNs} or {@code delayNs} is out of range
     */
    public static List<Complex> asImplemented(LinearModel model, GainSet gains, long periodNs,
            long delayNs, long filterTimeConstantNs) {
        DiscreteModel discrete = DiscreteModel.zeroOrderHold(model, periodNs, delayNs);
        double periodS = periodNs * 1e-9;
        double alpha = VelocityEstimator.smoothing(periodNs, filterTimeConstantNs);
        double[] k = gains.gains();
        double[] angleGains = {k[PendulumState.THETA1], k[PendulumState.THETA2]};
        double[] rateGains = {k[PendulumState.THETA1_RATE], k[PendulumState.THETA2_RATE]};
        int[] angleIndex = {PendulumState.THETA1, PendulumState.THETA2};

        // z = [x (0..3), θprev (4..5), vprev (6..7), uprev (8)]
        int n = 9;
        double[] control = new double[n]; // u[k] = control · z
        for (int j = 0; j < 2; j++) {
            control[angleIndex[j]] = -(angleGains[j] + alpha / periodS * rateGains[j]);
            control[4 + j] = alpha / periodS * rateGains[j];
            control[6 + j] = -(1.0 - alpha) * rateGains[j];
        }
        double[][] phi = discrete.phi();
        double[][] gammaNow = discrete.gammaNow();
        double[][] gammaPrevious = discrete.gammaPrevious();
        double[][] closed = new double[n][n];
        for (int i = 0; i < 4; i++) {
            for (int j = 0; j < 4; j++) {
                closed[i][j] = phi[i][j];
            }
            for (int j = 0; j < n; j++) {
                closed[i][j] += gammaNow[i][0] * control[j];
            }
            closed[i][8] += gammaPrevious[i][0];
        }
        for (int j = 0; j < 2; j++) {
            closed[4 + j][angleIndex[j]] = 1.0;
            closed[6 + j][6 + j] = 1.0 - alpha;
            closed[6 + j][angleIndex[j]] += alpha / periodS;
            closed[6 + j][4 + j] -= alpha / periodS;
        }
        System.arraycopy(control, 0, closed[8], 0, n);
        return Eigenvalues.of(closed);
    }

    /**
     * The largest modulus: below 1 for a stable loop.
     *
     * @param eigenvalues the loop's eigenvalues, at least one
     * @return the spectral radius
     * @throws java.util.NoSuchElementException when {@code eigenvalues} is empty
     */
    public static double spectralRadius(List<Complex> eigenvalues) {
        return eigenvalues.stream().mapToDouble(Complex::abs).max().orElseThrow();
    }

    /**
     * The slowest decay rate of the loop, {@code −ln(ρ) / T} for spectral radius ρ: the margin
     * inside the unit circle expressed as a continuous-time rate, comparable across periods.
     *
     * @param eigenvalues the loop's discrete-time eigenvalues, at least one
     * @param periodNs    the control period T they were computed for, in nanoseconds
     * @return the rate in 1/s; negative for an unstable loop
     */
    public static double slowestDecayRatePerS(List<Complex> eigenvalues, long periodNs) {
        return -Math.log(spectralRadius(eigenvalues)) / (periodNs * 1e-9);
    }

    /**
     * Throws unless every eigenvalue lies strictly inside the circle of radius
     * {@code e^{−σ T}}, i.e. every mode decays at least at {@code minDecayRatePerS} = σ.
     *
     * @param eigenvalues      the loop's discrete-time eigenvalues, at least one
     * @param periodNs         the control period T they were computed for, in nanoseconds
     * @param minDecayRatePerS σ, in 1/s; 0 asks for plain stability
     * @param what             names the loop in the exception's message
     * @throws IllegalStateException naming the offending radius and eigenvalues
     */
    public static void requireStable(List<Complex> eigenvalues, long periodNs,
            double minDecayRatePerS, String what) {
        double bound = Math.exp(-minDecayRatePerS * periodNs * 1e-9);
        double radius = spectralRadius(eigenvalues);
        if (!(radius < bound)) {
            throw new IllegalStateException(what + ": spectral radius " + radius
                    + " is not below e^(-" + minDecayRatePerS + "/s * " + periodNs * 1e-9
                    + " s) = " + bound + "; eigenvalues " + eigenvalues);
        }
    }
}
