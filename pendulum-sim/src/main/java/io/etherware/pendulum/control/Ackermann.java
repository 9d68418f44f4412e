package io.etherware.pendulum.control;

import io.etherware.pendulum.linalg.Complex;
import io.etherware.pendulum.linalg.Matrices;
import java.util.List;

/**
 * Pole placement for a single-input system by Ackermann's formula,
 * {@code K = [0 … 0 1] W_c⁻¹ φ(A)} with {@code W_c = [B, AB, …, A^(n-1) B]} and {@code φ} the
 * desired characteristic polynomial, so that {@code A − B K} has exactly the requested poles.
 * Works alike for continuous ({@code ẋ = Ax + Bu}) and discrete ({@code x⁺ = Φx + Γu}) models.
 *
 * <p>Stateless and thread-safe; design-time only.
 */
public final class Ackermann {

    private Ackermann() {}

    /**
     * The state-feedback gain row K placing the eigenvalues of {@code A − B K} at {@code poles}.
     *
     * @param a n×n state matrix
     * @param b n×1 input matrix
     * @param poles n poles; complex ones must come in conjugate pairs
     * @return K, n entries, so that {@code u = −K x}
     * @throws IllegalArgumentException if the counts disagree, the poles are not closed under
     *     conjugation, or (A, B) is not controllable
     */
    public static double[] gain(double[][] a, double[][] b, List<Complex> poles) {
        int n = a.length;
        if (b.length != n || b[0].length != 1) {
            throw new IllegalArgumentException("Ackermann needs a single input: B must be " + n
                    + "x1, got " + b.length + "x" + b[0].length);
        }
        if (poles.size() != n) {
            throw new IllegalArgumentException("poles=" + poles + ": need exactly " + n
                    + " poles for a " + n + "-state system");
        }
        double[] coefficients = realPolynomial(poles);

        double[][] controllability = new double[n][n];
        double[][] column = Matrices.copy(b);
        for (int j = 0; j < n; j++) {
            for (int i = 0; i < n; i++) {
                controllability[i][j] = column[i][0];
            }
            column = Matrices.multiply(a, column);
        }
        // φ(A) = A^n + c[n-1] A^(n-1) + … + c[0] I, by Horner's scheme.
        double[][] phi = Matrices.identity(n);
        for (int k = n - 1; k >= 0; k--) {
            phi = Matrices.add(Matrices.multiply(phi, a), Matrices.scale(Matrices.identity(n),
                    coefficients[k]));
        }
        // K = e_nᵀ W_c⁻¹ φ(A): solve W_cᵀ y = e_n, then K = yᵀ φ(A).
        double[][] transposed = new double[n][n];
        for (int i = 0; i < n; i++) {
            for (int j = 0; j < n; j++) {
                transposed[i][j] = controllability[j][i];
            }
        }
        double[][] unit = new double[n][1];
        unit[n - 1][0] = 1.0;
        double[][] y;
        try {
            y = Matrices.solve(transposed, unit);
        } catch (IllegalArgumentException singular) {
            throw new IllegalArgumentException("(A, B) is not controllable: the controllability"
                    + " matrix is singular (" + singular.getMessage() + ")", singular);
        }
        double[] gains = new double[n];
        for (int j = 0; j < n; j++) {
            double sum = 0.0;
            for (int i = 0; i < n; i++) {
                sum += y[i][0] * phi[i][j];
            }
            gains[j] = sum;
        }
        return gains;
    }

    /**
     * The coefficients {@code c[0..n-1]} of the monic polynomial {@code Π (s − p_i)}, lowest
     * degree first (the leading 1 omitted).
     */
    static double[] realPolynomial(List<Complex> roots) {
        int n = roots.size();
        Complex[] poly = new Complex[n + 1];
        poly[0] = Complex.real(1.0);
        for (int i = 1; i <= n; i++) {
            poly[i] = Complex.real(0.0);
        }
        // poly holds coefficients highest degree first while multiplying by (s - root).
        int degree = 0;
        for (Complex root : roots) {
            for (int k = degree + 1; k >= 1; k--) {
                poly[k] = poly[k].minus(root.times(poly[k - 1]));
            }
            degree++;
        }
        double scale = 1.0;
        for (Complex root : roots) {
            scale = Math.max(scale, root.abs());
        }
        double[] coefficients = new double[n];
        for (int k = 1; k <= n; k++) {
            Complex c = poly[k];
            if (Math.abs(c.im()) > 1e-9 * Math.pow(scale, k)) {
                throw new IllegalArgumentException("poles=" + roots
                        + ": complex poles must come in conjugate pairs");
            }
            coefficients[n - k] = c.re();
        }
        return coefficients;
    }
}
