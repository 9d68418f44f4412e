package io.etherware.pendulum.linalg;

import static org.junit.jupiter.api.Assertions.assertEquals;

import org.junit.jupiter.api.Test;

class MatrixExponentialTest {

    @Test
    void shouldRotateWhenExponentiatingASkewMatrix() {
        double angle = 2.5;
        double[][] rotation = MatrixExponential.exp(new double[][] {{0, -angle}, {angle, 0}});
        assertEquals(Math.cos(angle), rotation[0][0], 1e-14);
        assertEquals(-Math.sin(angle), rotation[0][1], 1e-14);
        assertEquals(Math.sin(angle), rotation[1][0], 1e-14);
        assertEquals(Math.cos(angle), rotation[1][1], 1e-14);
    }

    @Test
    void shouldMatchClosedFormForAJordanBlockWithLargeNorm() {
        // exp([[a, 1], [0, a]] t) = e^{at} [[1, t], [0, 1]]
        double a = -3.0;
        double t = 7.0;
        double[][] result = MatrixExponential.exp(new double[][] {{a * t, t}, {0, a * t}});
        double expected = Math.exp(a * t);
        assertEquals(expected, result[0][0], 1e-13 * expected + 1e-300);
        assertEquals(expected * t, result[0][1], 1e-12 * expected * t);
        assertEquals(0.0, result[1][0], 0.0);
        assertEquals(expected, result[1][1], 1e-13 * expected);
    }

    @Test
    void shouldSatisfyTheSemigroupProperty() {
        double[][] a = {{0.1, 2.0, -1.0}, {0.3, -4.0, 0.5}, {1.5, 0.2, -0.7}};
        double[][] once = MatrixExponential.exp(Matrices.scale(a, 2.0));
        double[][] half = MatrixExponential.exp(a);
        double[][] twice = Matrices.multiply(half, half);
        assertEquals(0.0, Matrices.maxAbsDifference(once, twice), 1e-12 * Matrices.normOne(once));
    }
}
