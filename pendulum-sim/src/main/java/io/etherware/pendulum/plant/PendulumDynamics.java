package io.etherware.pendulum.plant;

import static io.etherware.pendulum.plant.PendulumState.THETA1_RATE;
import static io.etherware.pendulum.plant.PendulumState.THETA2;
import static io.etherware.pendulum.plant.PendulumState.THETA2_RATE;

/**
 * Equation (1) of the paper, {@code M(q) q̈ + C(q, q̇) q̇ + G(q) = τ} with {@code τ = [u, 0]} plus
 * optional viscous friction, as {@code ẋ = f(x, u)} for {@code x = [θ1, θ̇1, θ2, θ̇2]}:
 *
 * <pre>
 * M = [ J1 + m(l1² + l2² sin²θ2)    m l1 l2 cos θ2 ]
 *     [ m l1 l2 cos θ2              J2 + m l2²     ]
 * C q̇ = [ 2 m l2² sinθ2 cosθ2 θ̇1 θ̇2 − m l1 l2 sinθ2 θ̇2² ]
 *       [ −m l2² sinθ2 cosθ2 θ̇1²                      ]
 * G = [ 0, −m g l2 sin θ2 ]
 * </pre>
 *
 * This is the Euler-Lagrange equation of {@code L = ½ q̇ᵀ M(q) q̇ − m g l2 cos θ2}, so with
 * {@code u = 0} and no friction the {@link #energyJ energy} is conserved; the tests check that.
 *
 * <p>Immutable and allocation-free: safe to share between threads.
 */
public final class PendulumDynamics {

    private final PendulumParameters parameters;
    private final double armTermKgM2;      // J1 + m l1²
    private final double couplingKgM2;     // m l1 l2
    private final double swingKgM2;        // m l2²
    private final double pendulumTermKgM2; // J2 + m l2²
    private final double gravityTorqueNm;  // m g l2

    /**
     * Dynamics for the given parameters, with the constant terms of equation (1) precomputed.
     *
     * @param parameters the pendulum's parameters
     */
    public PendulumDynamics(PendulumParameters parameters) {
        this.parameters = parameters;
        double m = parameters.pendulumMassKg();
        double l1 = parameters.armLengthM();
        double l2 = parameters.pendulumCenterOfMassM();
        this.armTermKgM2 = parameters.armInertiaKgM2() + m * l1 * l1;
        this.couplingKgM2 = m * l1 * l2;
        this.swingKgM2 = m * l2 * l2;
        this.pendulumTermKgM2 = parameters.pendulumInertiaKgM2() + m * l2 * l2;
        this.gravityTorqueNm = m * parameters.gravityMPerS2() * l2;
    }

    /**
     * The parameters.
     *
     * @return the parameters these dynamics were built from
     */
    public PendulumParameters parameters() {
        return parameters;
    }

    /**
     * Writes {@code ẋ = f(x, u)} into {@code dx}; allocation-free.
     *
     * @param x state {@code [θ1, θ̇1, θ2, θ̇2]}
     * @param torqueNm motor torque u at joint 1
     * @param dx output, may not alias {@code x}
     */
    public void derivative(double[] x, double torqueNm, double[] dx) {
        double rate1 = x[THETA1_RATE];
        double rate2 = x[THETA2_RATE];
        double sin = Math.sin(x[THETA2]);
        double cos = Math.cos(x[THETA2]);

        double m11 = armTermKgM2 + swingKgM2 * sin * sin;
        double m12 = couplingKgM2 * cos;
        double m22 = pendulumTermKgM2;

        // Right-hand sides τ − C q̇ − G − friction.
        double rhs1 = torqueNm
                - parameters.armDampingNmsPerRad() * rate1
                - 2.0 * swingKgM2 * sin * cos * rate1 * rate2
                + couplingKgM2 * sin * rate2 * rate2;
        double rhs2 = -parameters.pendulumDampingNmsPerRad() * rate2
                + swingKgM2 * sin * cos * rate1 * rate1
                + gravityTorqueNm * sin;

        double det = m11 * m22 - m12 * m12;
        dx[0] = rate1;
        dx[1] = (m22 * rhs1 - m12 * rhs2) / det;
        dx[2] = rate2;
        dx[3] = (m11 * rhs2 - m12 * rhs1) / det;
    }

    /**
     * Total mechanical energy {@code ½ q̇ᵀ M q̇ + m g l2 (1 + cos θ2)}: zero hanging at rest,
     * {@code 2 m g l2} upright at rest. Allocation-free.
     *
     * @param x state {@code [θ1, θ̇1, θ2, θ̇2]}, in rad and rad/s
     * @return the energy, in joules
     */
    public double energyJ(double[] x) {
        double rate1 = x[THETA1_RATE];
        double rate2 = x[THETA2_RATE];
        double sin = Math.sin(x[THETA2]);
        double cos = Math.cos(x[THETA2]);
        double m11 = armTermKgM2 + swingKgM2 * sin * sin;
        double m12 = couplingKgM2 * cos;
        double kinetic = 0.5 * (m11 * rate1 * rate1 + 2.0 * m12 * rate1 * rate2
                + pendulumTermKgM2 * rate2 * rate2);
        return kinetic + gravityTorqueNm * (1.0 + cos);
    }

    /** The mass matrix M(θ2) at upright, {@code θ2 = 0}: {@code [[J1 + m l1², m l1 l2], [m l1 l2, J2 + m l2²]]}. */
    double[][] uprightMassMatrix() {
        return new double[][] {{armTermKgM2, couplingKgM2}, {couplingKgM2, pendulumTermKgM2}};
    }

    /** {@code m g l2}, the gravity torque per radian at upright. */
    double gravityTorqueNm() {
        return gravityTorqueNm;
    }
}
