package io.etherware.pendulum.linalg;

import static org.junit.jupiter.api.Assertions.assertEquals;
import static org.junit.jupiter.api.Assertions.assertThrows;

import java.util.Comparator;
import java.util.List;
import java.util.Random;
import org.junit.jupiter.api.Test;

class EigenvaluesTest {

    @Test
    void shouldFindRealAndComplexRootsOfACompanionMatrix() {
        // (s + 1)(s - 2)(s^2 + 2s + 5): roots -1, 2, -1 +- 2i.
        // Expanded: s^4 + s^3 + s^2 - 9 s - 10.
        double[][] companion = {
            {0, 1, 0, 0},
            {0, 0, 1, 0},
            {0, 0, 0, 1},
            {10, 9, -1, -1},
        };
        List<Complex> roots = Eigenvalues.of(companion);

        assertContains(roots, new Complex(2, 0));
        assertContains(roots, new Complex(-1, 0));
        assertContains(roots, new Complex(-1, 2));
        assertContains(roots, new Complex(-1, -2));
        assertEquals(Math.sqrt(5), roots.getFirst().abs(), 1e-10);
    }

    @Test
    void shouldMatchAKnownSpectrumAfterARandomSimilarityTransform() {
        Random random = new Random(42);
        int n = 9;
        double[][] diagonalBlocks = new double[n][n];
        double[] expectedReal = {0.95, -0.3, 0.5, 0.2, 0.0, 0.99, 0.7};
        for (int i = 0; i < expectedReal.length; i++) {
            diagonalBlocks[i][i] = expectedReal[i];
        }
        // A rotation block with eigenvalues 0.6 +- 0.7i.
        diagonalBlocks[7][7] = 0.6;
        diagonalBlocks[7][8] = 0.7;
        diagonalBlocks[8][7] = -0.7;
        diagonalBlocks[8][8] = 0.6;
        double[][] transform = new double[n][n];
        for (int i = 0; i < n; i++) {
            for (int j = 0; j < n; j++) {
                transform[i][j] = random.nextGaussian() + (i == j ? 3 : 0);
            }
        }
        double[][] similar = Matrices.multiply(Matrices.multiply(transform, diagonalBlocks),
                Matrices.inverse(transform));

        List<Complex> eigenvalues = Eigenvalues.of(similar);

        assertEquals(n, eigenvalues.size());
        for (double value : expectedReal) {
            assertContains(eigenvalues, Complex.real(value));
        }
        assertContains(eigenvalues, new Complex(0.6, 0.7));
        assertContains(eigenvalues, new Complex(0.6, -0.7));
        assertEquals(0.99, Eigenvalues.spectralRadius(similar), 1e-9);
    }

    @Test
    void shouldHandleRepeatedZeroEigenvalues() {
        double[][] doubleIntegratorPlusUnstable = {
            {0, 1, 0, 0},
            {0, 0, 3, 0},
            {0, 0, 0, 1},
            {0, 0, 49, 0},
        };
        List<Complex> eigenvalues = Eigenvalues.of(doubleIntegratorPlusUnstable);
        assertEquals(7.0, eigenvalues.getFirst().re(), 1e-9);
        assertEquals(7.0, Eigenvalues.spectralAbscissa(doubleIntegratorPlusUnstable), 1e-9);
        assertContains(eigenvalues, Complex.real(-7));
        long nearZero = eigenvalues.stream().filter(z -> z.abs() < 1e-6).count();
        assertEquals(2, nearZero);
    }

    @Test
    void shouldRejectANonSquareMatrix() {
        var error = assertThrows(IllegalArgumentException.class,
                () -> Eigenvalues.of(new double[][] {{1, 2}, {3}}));
        assertEquals(true, error.getMessage().contains("square"));
    }

    private static void assertContains(List<Complex> values, Complex expected) {
        Complex nearest = values.stream()
                .min(Comparator.comparingDouble(z -> z.minus(expected).abs()))
                .orElseThrow();
        assertEquals(0.0, nearest.minus(expected).abs(), 1e-8,
                () -> "expected " + expected + " among " + values);
    }
}
