package io.etherware.pendulum.linalg;

/**
 * The matrix exponential e^A by scaling and squaring with a diagonal (6,6) Padé approximant
 * (Moler and Van Loan, "Nineteen dubious ways", method 3; Golub and Van Loan, Algorithm 11.3.1).
 *
 * <p>A is scaled by 2^-s so that ||A/2^s||₁ ≤ 1/2; for q = 6 the relative backward error bound is
 * then 2^(3-2q) (q!)² / ((2q)! (2q+1)!) ≈ 3.4e-16, i.e. round-off. The result is squared s times.
 * Stateless and thread-safe.
 */
public final class MatrixExponential {

    private static final int PADE_DEGREE = 6;

    private MatrixExponential() {}

    /**
     * e^A for a square matrix A.
     *
     * @param a a square, finite matrix; not modified
     * @return e^A, a new matrix of the same size
     * @throws IllegalArgumentException when {@code a} is empty, not square or not finite
     */
    public static double[][] exp(double[][] a) {
        int n = a.length;
        if (n == 0 || a[0].length != n) {
            throw new IllegalArgumentException("exp needs a square matrix, got " + n + "x"
                    + (n == 0 ? 0 : a[0].length));
        }
        double norm = Matrices.normOne(a);
        if (!Double.isFinite(norm)) {
            throw new IllegalArgumentException("exp needs a finite matrix, got ||A||1=" + norm);
        }
        int squarings = norm <= 0.5 ? 0 : Math.getExponent(norm / 0.5) + 1;
        double[][] scaled = Matrices.scale(a, Math.scalb(1.0, -squarings));

        double[][] numerator = Matrices.identity(n);
        double[][] denominator = Matrices.identity(n);
        double[][] power = Matrices.identity(n);
        double coefficient = 1.0;
        for (int k = 1; k <= PADE_DEGREE; k++) {
            coefficient *= (double) (PADE_DEGREE - k + 1) / (k * (2.0 * PADE_DEGREE - k + 1));
            power = Matrices.multiply(power, scaled);
            double[][] term = Matrices.scale(power, coefficient);
            numerator = Matrices.add(numerator, term);
            denominator = (k % 2 == 0) ? Matrices.add(denominator, term)
                    : Matrices.subtract(denominator, term);
        }
        double[][] result = Matrices.solve(denominator, numerator);
        for (int i = 0; i < squarings; i++) {
            result = Matrices.multiply(result, result);
        }
        return result;
    }
}
