package io.etherware.pendulum.plant;

import static org.junit.jupiter.api.Assertions.assertEquals;
import static org.junit.jupiter.api.Assertions.assertTrue;

import io.etherware.pendulum.linalg.Complex;
import io.etherware.pendulum.linalg.Matrices;
import org.junit.jupiter.api.Test;

class LinearModelTest {

    @Test
    void shouldMatchTheNumericalJacobianAtUpright() {
        PendulumParameters parameters = PendulumParameters.defaults().withDamping(2e-3, 5e-5);
        LinearModel analytic = LinearModel.linearize(parameters, 0.7);
        LinearModel numerical = LinearModel.numerical(new PendulumDynamics(parameters),
                PendulumState.upright(0.7), 0.0, 1e-6);

        double scaleA = Matrices.normOne(analytic.a());
        double scaleB = Matrices.normOne(analytic.b());
        assertTrue(Matrices.maxAbsDifference(analytic.a(), numerical.a()) < 1e-7 * scaleA,
                () -> "analytic\n" + analytic + "numerical\n" + numerical);
        assertTrue(Matrices.maxAbsDifference(analytic.b(), numerical.b()) < 1e-7 * scaleB,
                () -> "analytic\n" + analytic + "numerical\n" + numerical);
    }

    @Test
    void shouldDifferFromTheNumericalJacobianAwayFromTheEquilibrium() {
        PendulumParameters parameters = PendulumParameters.defaults();
        LinearModel analytic = LinearModel.linearize(parameters, 0.0);
        LinearModel elsewhere = LinearModel.numerical(new PendulumDynamics(parameters),
                new PendulumState(0, 2.0, 0.6, 1.0), 0.0, 1e-6);
        assertTrue(Matrices.maxAbsDifference(analytic.a(), elsewhere.a()) > 1.0);
    }

    @Test
    void shouldHaveOneUnstableRealEigenvalueAtUpright() {
        PendulumParameters parameters = PendulumParameters.defaults();
        LinearModel model = LinearModel.linearize(parameters, 0.0);
        Complex unstable = model.mostUnstableEigenvalue();

        // Closed form without friction: λ² = m g l2 (J1 + m l1²) / det(M0).
        double m = parameters.pendulumMassKg();
        double l1 = parameters.armLengthM();
        double l2 = parameters.pendulumCenterOfMassM();
        double m11 = parameters.armInertiaKgM2() + m * l1 * l1;
        double m22 = parameters.pendulumInertiaKgM2() + m * l2 * l2;
        double det = m11 * m22 - (m * l1 * l2) * (m * l1 * l2);
        double expected = Math.sqrt(m * parameters.gravityMPerS2() * l2 * m11 / det);
        System.out.printf("open-loop eigenvalues %s; unstable %s rad/s%n",
                model.eigenvalues(), unstable);

        assertEquals(expected, unstable.re(), 1e-9 * expected);
        assertEquals(0.0, unstable.im(), 0.0);
        long unstableCount = model.eigenvalues().stream().filter(z -> z.re() > 1e-6).count();
        assertEquals(1, unstableCount);
    }
}
