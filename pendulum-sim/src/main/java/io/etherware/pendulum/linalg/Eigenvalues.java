package io.etherware.pendulum.linalg;

import java.util.ArrayList;
import java.util.Comparator;
import java.util.List;

/**
 * Eigenvalues of a small real square matrix: balancing, reduction to upper Hessenberg form by
 * stabilized elementary similarity transforms, then the Francis implicit double-shift QR
 * iteration (the classical EISPACK {@code balanc/elmhes/hqr} sequence; see Golub and Van Loan,
 * Matrix Computations, Section 7.5, and Press et al., Numerical Recipes, Section 11.5-11.6).
 *
 * <p>Good for the 4×4 to ~20×20 matrices of controller design; stateless and thread-safe.
 */
public final class Eigenvalues {

    private static final double EPS = Math.ulp(1.0);
    private static final int MAX_ITERATIONS_PER_EIGENVALUE = 60;

    private Eigenvalues() {}

    /**
     * The eigenvalues of {@code a}, sorted by decreasing modulus then decreasing real part.
     * Complex eigenvalues come in conjugate pairs.
     *
     * @param a a square, finite matrix; not modified
     * @return the n eigenvalues, repeated by multiplicity; a new list
     * @throws IllegalArgumentException if {@code a} is not square or not finite
     * @throws ArithmeticException if the QR iteration does not converge
     */
    public static List<Complex> of(double[][] a) {
        int n = a.length;
        for (double[] row : a) {
            if (row.length != n) {
                throw new IllegalArgumentException("eigenvalues need a square matrix, got a row of "
                        + row.length + " in a matrix of " + n + " rows");
            }
            for (double value : row) {
                if (!Double.isFinite(value)) {
                    throw new IllegalArgumentException("eigenvalues need a finite matrix, found " + value);
                }
            }
        }
        double[][] h = Matrices.copy(a);
        balance(h);
        reduceToHessenberg(h);
        List<Complex> result = hessenbergQr(h);
        result.sort(Comparator.comparingDouble(Complex::abs).reversed()
                .thenComparing(Comparator.comparingDouble(Complex::re).reversed())
                .thenComparing(Comparator.comparingDouble(Complex::im).reversed()));
        return result;
    }

    /**
     * The largest eigenvalue modulus (spectral radius): below 1 for a stable discrete-time system.
     *
     * @param a a non-empty, square, finite matrix; not modified
     * @return {@code max |λ|}
     * @throws IllegalArgumentException if {@code a} is not square or not finite
     * @throws ArithmeticException if the QR iteration does not converge
     */
    public static double spectralRadius(double[][] a) {
        return of(a).getFirst().abs();
    }

    /**
     * The largest real part of the eigenvalues (spectral abscissa): below 0 for a stable
     * continuous-time system.
     *
     * @param a a non-empty, square, finite matrix; not modified
     * @return {@code max Re(λ)}
     * @throws IllegalArgumentException if {@code a} is not square or not finite
     * @throws ArithmeticException if the QR iteration does not converge
     */
    public static double spectralAbscissa(double[][] a) {
        return of(a).stream().mapToDouble(Complex::re).max().orElseThrow();
    }

    /** Diagonal similarity scaling by powers of two so that row and column norms are comparable. */
    private static void balance(double[][] a) {
        final double radix = 2.0;
        final double radixSquared = radix * radix;
        int n = a.length;
        boolean done = false;
        while (!done) {
            done = true;
            for (int i = 0; i < n; i++) {
                double rowNorm = 0.0;
                double colNorm = 0.0;
                for (int j = 0; j < n; j++) {
                    if (j != i) {
                        colNorm += Math.abs(a[j][i]);
                        rowNorm += Math.abs(a[i][j]);
                    }
                }
                if (colNorm == 0.0 || rowNorm == 0.0) {
                    continue;
                }
                double g = rowNorm / radix;
                double f = 1.0;
                double sum = colNorm + rowNorm;
                while (colNorm < g) {
                    f *= radix;
                    colNorm *= radixSquared;
                }
                g = rowNorm * radix;
                while (colNorm > g) {
                    f /= radix;
                    colNorm /= radixSquared;
                }
                if ((colNorm + rowNorm) / f < 0.95 * sum) {
                    done = false;
                    double inverse = 1.0 / f;
                    for (int j = 0; j < n; j++) {
                        a[i][j] *= inverse;
                    }
                    for (int j = 0; j < n; j++) {
                        a[j][i] *= f;
                    }
                }
            }
        }
    }

    /** Gaussian elimination with pivoting, as similarity transforms, to upper Hessenberg form. */
    private static void reduceToHessenberg(double[][] a) {
        int n = a.length;
        for (int m = 1; m < n - 1; m++) {
            double pivotValue = 0.0;
            int pivot = m;
            for (int j = m; j < n; j++) {
                if (Math.abs(a[j][m - 1]) > Math.abs(pivotValue)) {
                    pivotValue = a[j][m - 1];
                    pivot = j;
                }
            }
            if (pivot != m) {
                for (int j = m - 1; j < n; j++) {
                    double tmp = a[pivot][j];
                    a[pivot][j] = a[m][j];
                    a[m][j] = tmp;
                }
                for (int j = 0; j < n; j++) {
                    double tmp = a[j][pivot];
                    a[j][pivot] = a[j][m];
                    a[j][m] = tmp;
                }
            }
            if (pivotValue != 0.0) {
                for (int i = m + 1; i < n; i++) {
                    double y = a[i][m - 1];
                    if (y != 0.0) {
                        y /= pivotValue;
                        a[i][m - 1] = 0.0;
                        for (int j = m; j < n; j++) {
                            a[i][j] -= y * a[m][j];
                        }
                        for (int j = 0; j < n; j++) {
                            a[j][m] += y * a[j][i];
                        }
                    }
                }
            }
        }
        for (int i = 2; i < n; i++) {
            for (int j = 0; j < i - 1; j++) {
                a[i][j] = 0.0;
            }
        }
    }

    /** Francis double-shift QR on an upper Hessenberg matrix (destroyed). */
    private static List<Complex> hessenbergQr(double[][] a) {
        int n = a.length;
        double[] wr = new double[n];
        double[] wi = new double[n];
        double norm = 0.0;
        for (int i = 0; i < n; i++) {
            for (int j = Math.max(i - 1, 0); j < n; j++) {
                norm += Math.abs(a[i][j]);
            }
        }
        int nn = n - 1;
        double t = 0.0;
        double p = 0.0;
        double q = 0.0;
        double r = 0.0;
        double x;
        double y;
        double z;
        double w;
        double s;
        while (nn >= 0) {
            int iterations = 0;
            int l;
            do {
                // Look for a single small subdiagonal element to split the matrix.
                for (l = nn; l >= 1; l--) {
                    s = Math.abs(a[l - 1][l - 1]) + Math.abs(a[l][l]);
                    if (s == 0.0) {
                        s = norm;
                    }
                    if (Math.abs(a[l][l - 1]) <= EPS * s) {
                        a[l][l - 1] = 0.0;
                        break;
                    }
                }
                x = a[nn][nn];
                if (l == nn) {
                    // One root found.
                    wr[nn] = x + t;
                    wi[nn] = 0.0;
                    nn--;
                } else {
                    y = a[nn - 1][nn - 1];
                    w = a[nn][nn - 1] * a[nn - 1][nn];
                    if (l == nn - 1) {
                        // Two roots found.
                        p = 0.5 * (y - x);
                        q = p * p + w;
                        z = Math.sqrt(Math.abs(q));
                        x += t;
                        if (q >= 0.0) {
                            z = p + Math.copySign(z, p);
                            wr[nn - 1] = x + z;
                            wr[nn] = z != 0.0 ? x - w / z : x + z;
                            wi[nn - 1] = 0.0;
                            wi[nn] = 0.0;
                        } else {
                            wr[nn - 1] = x + p;
                            wr[nn] = x + p;
                            wi[nn - 1] = -z;
                            wi[nn] = z;
                        }
                        nn -= 2;
                    } else {
                        if (iterations == MAX_ITERATIONS_PER_EIGENVALUE) {
                            throw new ArithmeticException("QR iteration did not converge after "
                                    + iterations + " iterations");
                        }
                        if (iterations == 10 || iterations == 20 || iterations == 40) {
                            // Exceptional shift, to break cycles.
                            t += x;
                            for (int i = 0; i <= nn; i++) {
                                a[i][i] -= x;
                            }
                            s = Math.abs(a[nn][nn - 1]) + Math.abs(a[nn - 1][nn - 2]);
                            x = 0.75 * s;
                            y = x;
                            w = -0.4375 * s * s;
                        }
                        iterations++;
                        // Form the shift and look for two consecutive small subdiagonal elements.
                        int m;
                        for (m = nn - 2; m >= l; m--) {
                            z = a[m][m];
                            r = x - z;
                            s = y - z;
                            p = (r * s - w) / a[m + 1][m] + a[m][m + 1];
                            q = a[m + 1][m + 1] - z - r - s;
                            r = a[m + 2][m + 1];
                            s = Math.abs(p) + Math.abs(q) + Math.abs(r);
                            p /= s;
                            q /= s;
                            r /= s;
                            if (m == l) {
                                break;
                            }
                            double u = Math.abs(a[m][m - 1]) * (Math.abs(q) + Math.abs(r));
                            double v = Math.abs(p) * (Math.abs(a[m - 1][m - 1]) + Math.abs(z)
                                    + Math.abs(a[m + 1][m + 1]));
                            if (u <= EPS * v) {
                                break;
                            }
                        }
                        for (int i = m + 2; i <= nn; i++) {
                            a[i][i - 2] = 0.0;
                            if (i != m + 2) {
                                a[i][i - 3] = 0.0;
                            }
                        }
                        // Double QR step on rows l..nn and columns m..nn.
                        for (int k = m; k <= nn - 1; k++) {
                            if (k != m) {
                                p = a[k][k - 1];
                                q = a[k + 1][k - 1];
                                r = 0.0;
                                if (k != nn - 1) {
                                    r = a[k + 2][k - 1];
                                }
                                x = Math.abs(p) + Math.abs(q) + Math.abs(r);
                                if (x != 0.0) {
                                    p /= x;
                                    q /= x;
                                    r /= x;
                                }
                            }
                            s = Math.copySign(Math.sqrt(p * p + q * q + r * r), p);
                            if (s != 0.0) {
                                if (k == m) {
                                    if (l != m) {
                                        a[k][k - 1] = -a[k][k - 1];
                                    }
                                } else {
                                    a[k][k - 1] = -s * x;
                                }
                                p += s;
                                x = p / s;
                                y = q / s;
                                z = r / s;
                                q /= p;
                                r /= p;
                                for (int j = k; j <= nn; j++) {
                                    p = a[k][j] + q * a[k + 1][j];
                                    if (k != nn - 1) {
                                        p += r * a[k + 2][j];
                                        a[k + 2][j] -= p * z;
                                    }
                                    a[k + 1][j] -= p * y;
                                    a[k][j] -= p * x;
                                }
                                int last = Math.min(nn, k + 3);
                                for (int i = l; i <= last; i++) {
                                    p = x * a[i][k] + y * a[i][k + 1];
                                    if (k != nn - 1) {
                                        p += z * a[i][k + 2];
                                        a[i][k + 2] -= p * r;
                                    }
                                    a[i][k + 1] -= p * q;
                                    a[i][k] -= p;
                                }
                            }
                        }
                    }
                }
            } while (nn >= 0 && l < nn - 1);
        }
        List<Complex> result = new ArrayList<>(n);
        for (int i = 0; i < n; i++) {
            result.add(new Complex(wr[i], wi[i]));
        }
        return result;
    }
}
