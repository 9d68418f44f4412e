package io.etherware.pendulum.plant;

import io.etherware.pendulum.linalg.Complex;
import io.etherware.pendulum.linalg.Eigenvalues;
import io.etherware.pendulum.linalg.Matrices;
import java.util.List;

/**
 * A linear model {@code ẋ = A x + B u} of the pendulum about an equilibrium, paper equation (2).
 *
 * <p>Immutable: the accessors return copies. Thread-safe.
 */
public final class LinearModel {

    private final double[][] a;
    private final double[][] b;

    /**
     * A model from its matrices (copied).
     *
     * @param a the n×n state matrix
     * @param b the n×1 input matrix
     */
    public LinearModel(double[][] a, double[][] b) {
        int n = a.length;
        for (double[] row : a) {
            if (row.length != n) {
                throw new IllegalArgumentException("A must be square, got a row of " + row.length
                        + " in " + n + " rows");
            }
        }
        if (b.length != n || b[0].length != 1) {
            throw new IllegalArgumentException("B must be " + n + "x1, got " + b.length + "x"
                    + b[0].length);
        }
        this.a = Matrices.copy(a);
        this.b = Matrices.copy(b);
    }

    /**
     * The analytic linearization of equation (1) about {@code x0 = [θ1r, 0, 0, 0]}, {@code u0 = 0}.
     *
     * <p>At {@code θ2 = 0} the Coriolis terms are quadratic in the rates and vanish, and
     * {@code sin θ2 ≈ θ2}, so {@code M0 q̈ = [u − b1 θ̇1, m g l2 θ2 − b2 θ̇2]} with the constant upright
     * mass matrix {@code M0}. θ1 is a cyclic coordinate, so A and B do not depend on θ1r.
     *
     * @param parameters         the pendulum's parameters
     * @param theta1ReferenceRad θ1r, the arm angle of the equilibrium, in radians; finite
     * @return the 4-state model
     * @throws IllegalArgumentException when {@code theta1ReferenceRad} is not finite
     */
    public static LinearModel linearize(PendulumParameters parameters, double theta1ReferenceRad) {
        if (!Double.isFinite(theta1ReferenceRad)) {
            throw new IllegalArgumentException("theta1ReferenceRad=" + theta1ReferenceRad
                    + ": must be finite");
        }
        PendulumDynamics dynamics = new PendulumDynamics(parameters);
        double[][] m0 = dynamics.uprightMassMatrix();
        double m11 = m0[0][0];
        double m12 = m0[0][1];
        double m22 = m0[1][1];
        double det = m11 * m22 - m12 * m12;
        double mgl = dynamics.gravityTorqueNm();
        double b1 = parameters.armDampingNmsPerRad();
        double b2 = parameters.pendulumDampingNmsPerRad();
        double[][] a = {
            {0, 1, 0, 0},
            {0, -m22 * b1 / det, -m12 * mgl / det, m12 * b2 / det},
            {0, 0, 0, 1},
            {0, m12 * b1 / det, m11 * mgl / det, -m11 * b2 / det},
        };
        double[][] b = {{0}, {m22 / det}, {0}, {-m12 / det}};
        return new LinearModel(a, b);
    }

    /**
     * The Jacobians of {@code f} at {@code (x0, u0)} by central differences with step {@code h}
     * (relative to each variable's magnitude, at least {@code h}). For checking
     * {@link #linearize}.
     *
     * @param dynamics the nonlinear dynamics f
     * @param x0       the state to linearize about
     * @param u0       the torque to linearize about, in N·m
     * @param h        the relative difference step, e.g. {@code 1e-6}
     * @return the 4-state model
     */
    public static LinearModel numerical(PendulumDynamics dynamics, PendulumState x0, double u0,
            double h) {
        int n = PendulumState.SIZE;
        double[] base = x0.toArray();
        double[] plus = new double[n];
        double[] minus = new double[n];
        double[] work = new double[n];
        double[][] a = new double[n][n];
        for (int j = 0; j < n; j++) {
            double delta = h * Math.max(1.0, Math.abs(base[j]));
            System.arraycopy(base, 0, work, 0, n);
            work[j] = base[j] + delta;
            dynamics.derivative(work, u0, plus);
            work[j] = base[j] - delta;
            dynamics.derivative(work, u0, minus);
            for (int i = 0; i < n; i++) {
                a[i][j] = (plus[i] - minus[i]) / (2 * delta);
            }
        }
        double[][] b = new double[n][1];
        double delta = h * Math.max(1.0, Math.abs(u0));
        dynamics.derivative(base, u0 + delta, plus);
        dynamics.derivative(base, u0 - delta, minus);
        for (int i = 0; i < n; i++) {
            b[i][0] = (plus[i] - minus[i]) / (2 * delta);
        }
        return new LinearModel(a, b);
    }

    /**
     * The state matrix A.
     *
     * @return a copy of A, n×n
     */
    public double[][] a() {
        return Matrices.copy(a);
    }

    /**
     * The input matrix B.
     *
     * @return a copy of B, n×1
     */
    public double[][] b() {
        return Matrices.copy(b);
    }

    /**
     * The number of states.
     *
     * @return n, the size of A
     */
    public int order() {
        return a.length;
    }

    /**
     * The open-loop eigenvalues of A.
     *
     * @return the n eigenvalues, by decreasing modulus
     * @throws ArithmeticException if the eigenvalue iteration does not converge
     */
    public List<Complex> eigenvalues() {
        return Eigenvalues.of(a);
    }

    /**
     * The open-loop eigenvalue with the largest real part: the pendulum's unstable pole.
     *
     * @return the eigenvalue, in rad/s
     * @throws ArithmeticException if the eigenvalue iteration does not converge
     */
    public Complex mostUnstableEigenvalue() {
        return eigenvalues().stream()
                .max((p, q) -> Double.compare(p.re(), q.re()))
                .orElseThrow();
    }

    @Override
    public String toString() {
        return "A=\n" + Matrices.toString(a) + "B=\n" + Matrices.toString(b);
    }
}
