package io.etherware.pendulum.control;

import static org.junit.jupiter.api.Assertions.assertEquals;
import static org.junit.jupiter.api.Assertions.assertThrows;
import static org.junit.jupiter.api.Assertions.assertTrue;

import io.etherware.pendulum.linalg.Complex;
import io.etherware.pendulum.linalg.Eigenvalues;
import io.etherware.pendulum.linalg.Matrices;
import io.etherware.pendulum.plant.LinearModel;
import io.etherware.pendulum.plant.PendulumParameters;
import java.util.Comparator;
import java.util.List;
import org.junit.jupiter.api.Test;

class AckermannTest {

    private static final LinearModel PENDULUM = LinearModel.linearize(
            PendulumParameters.defaults().withDamping(1e-3, 2e-5), 0.0);

    @Test
    void shouldPlaceThePolesOfTheClosedLoopWhereAsked() {
        List<Complex> poles = List.of(new Complex(-3, 2), new Complex(-3, -2), Complex.real(-10),
                Complex.real(-12));
        double[] k = Ackermann.gain(PENDULUM.a(), PENDULUM.b(), poles);
        double[][] closed = Matrices.subtract(PENDULUM.a(), Matrices.multiply(PENDULUM.b(),
                new double[][] {k}));

        List<Complex> placed = Eigenvalues.of(closed);
        for (Complex pole : poles) {
            Complex nearest = placed.stream()
                    .min(Comparator.comparingDouble(z -> z.minus(pole).abs())).orElseThrow();
            assertEquals(0.0, nearest.minus(pole).abs(), 1e-6, () -> "placed " + placed);
        }
    }

    @Test
    void shouldRejectPolesThatAreNotConjugatePairs() {
        var error = assertThrows(IllegalArgumentException.class, () -> Ackermann.gain(PENDULUM.a(),
                PENDULUM.b(), List.of(new Complex(-3, 2), Complex.real(-3), Complex.real(-10),
                        Complex.real(-12))));
        assertTrue(error.getMessage().contains("conjugate pairs"), error.getMessage());
    }

    @Test
    void shouldRejectAnUncontrollableSystem() {
        double[][] a = {{-1, 0}, {0, -2}};
        double[][] b = {{1}, {0}};
        var error = assertThrows(IllegalArgumentException.class,
                () -> Ackermann.gain(a, b, List.of(Complex.real(-3), Complex.real(-4))));
        assertTrue(error.getMessage().contains("not controllable"), error.getMessage());
    }

    @Test
    void shouldRejectTheWrongNumberOfPoles() {
        var error = assertThrows(IllegalArgumentException.class,
                () -> Ackermann.gain(PENDULUM.a(), PENDULUM.b(), List.of(Complex.real(-1))));
        assertTrue(error.getMessage().contains("exactly 4"), error.getMessage());
    }
}
