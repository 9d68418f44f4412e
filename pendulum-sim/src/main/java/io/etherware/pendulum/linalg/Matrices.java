package io.etherware.pendulum.linalg;

import java.util.Arrays;

/**
 * Small dense matrix helpers on {@code double[rows][cols]} arrays, for design-time work (gain
 * design, discretization, eigenvalue checks) on matrices of a few rows.
 *
 * <p>Every method is a pure function: it never modifies its arguments and returns a new array.
 * Stateless and thread-safe. Not meant for a hot path.
 */
public final class Matrices {

    private Matrices() {}

    /**
     * The n×n identity.
     *
     * @param n the size, 0 or more
     * @return a new identity matrix
     */
    public static double[][] identity(int n) {
        double[][] result = new double[n][n];
        for (int i = 0; i < n; i++) {
            result[i][i] = 1.0;
        }
        return result;
    }

    /**
     * A deep copy.
     *
     * @param a a matrix; rows may differ in length
     * @return a new matrix with copies of the rows
     */
    public static double[][] copy(double[][] a) {
        double[][] result = new double[a.length][];
        for (int i = 0; i < a.length; i++) {
            result[i] = a[i].clone();
        }
        return result;
    }

    /**
     * A column vector (n×1) from its entries.
     *
     * @param entries the entries, top to bottom
     * @return a new n×1 matrix
     */
    public static double[][] column(double... entries) {
        double[][] result = new double[entries.length][1];
        for (int i = 0; i < entries.length; i++) {
            result[i][0] = entries[i];
        }
        return result;
    }

    /**
     * The matrix product.
     *
     * @param a an n×k matrix
     * @param b a k×m matrix
     * @return {@code a * b}, n×m
     * @throws IllegalArgumentException when the inner dimensions differ
     */
    public static double[][] multiply(double[][] a, double[][] b) {
        int n = a.length;
        int inner = b.length;
        int m = b[0].length;
        requireShape(a[0].length == inner, "multiply", a, b);
        double[][] result = new double[n][m];
        for (int i = 0; i < n; i++) {
            for (int k = 0; k < inner; k++) {
                double aik = a[i][k];
                if (aik == 0.0) {
                    continue;
                }
                for (int j = 0; j < m; j++) {
                    result[i][j] += aik * b[k][j];
                }
            }
        }
        return result;
    }

    /**
     * The sum.
     *
     * @param a a matrix
     * @param b a matrix of the same shape
     * @return {@code a + b}
     * @throws IllegalArgumentException when the shapes differ
     */
    public static double[][] add(double[][] a, double[][] b) {
        requireShape(a.length == b.length && a[0].length == b[0].length, "add", a, b);
        double[][] result = new double[a.length][a[0].length];
        for (int i = 0; i < a.length; i++) {
            for (int j = 0; j < a[0].length; j++) {
                result[i][j] = a[i][j] + b[i][j];
            }
        }
        return result;
    }

    /**
     * The difference.
     *
     * @param a a matrix
     * @param b a matrix of the same shape
     * @return {@code a - b}
     * @throws IllegalArgumentException when the shapes differ
     */
    public static double[][] subtract(double[][] a, double[][] b) {
        return add(a, scale(b, -1.0));
    }

    /**
     * The matrix times a scalar.
     *
     * @param a      a matrix
     * @param factor the scalar
     * @return {@code factor * a}
     */
    public static double[][] scale(double[][] a, double factor) {
        double[][] result = new double[a.length][a[0].length];
        for (int i = 0; i < a.length; i++) {
            for (int j = 0; j < a[0].length; j++) {
                result[i][j] = factor * a[i][j];
            }
        }
        return result;
    }

    /**
     * The maximum absolute column sum, ||a||₁.
     *
     * @param a a non-empty matrix
     * @return the norm, 0 or more; NaN or infinite when an entry is
     */
    public static double normOne(double[][] a) {
        double max = 0.0;
        for (int j = 0; j < a[0].length; j++) {
            double sum = 0.0;
            for (double[] row : a) {
                sum += Math.abs(row[j]);
            }
            max = Math.max(max, sum);
        }
        return max;
    }

    /**
     * The largest absolute entry difference between two matrices, for tests and tolerances.
     *
     * @param a a matrix
     * @param b a matrix of the same shape
     * @return {@code max |a[i][j] - b[i][j]|}
     * @throws IllegalArgumentException when the shapes differ
     */
    public static double maxAbsDifference(double[][] a, double[][] b) {
        requireShape(a.length == b.length && a[0].length == b[0].length, "compare", a, b);
        double max = 0.0;
        for (int i = 0; i < a.length; i++) {
            for (int j = 0; j < a[0].length; j++) {
                max = Math.max(max, Math.abs(a[i][j] - b[i][j]));
            }
        }
        return max;
    }

    /**
     * Solves {@code a x = b} by Gaussian elimination with partial pivoting.
     *
     * @param a an n×n matrix
     * @param b an n×m right-hand side
     * @return x, n×m
     * @throws IllegalArgumentException if {@code a} is singular to working precision, or the shapes
     *                                  do not fit
     */
    public static double[][] solve(double[][] a, double[][] b) {
        int n = a.length;
        requireShape(a[0].length == n && b.length == n, "solve", a, b);
        double[][] lu = copy(a);
        double[][] x = copy(b);
        int m = x[0].length;
        double scale = Math.max(normOne(a), Double.MIN_NORMAL);
        for (int col = 0; col < n; col++) {
            int pivot = col;
            for (int row = col + 1; row < n; row++) {
                if (Math.abs(lu[row][col]) > Math.abs(lu[pivot][col])) {
                    pivot = row;
                }
            }
            if (Math.abs(lu[pivot][col]) <= 1e-14 * scale) {
                throw new IllegalArgumentException(
                        "matrix is singular to working precision (pivot " + lu[pivot][col]
                                + " in column " + col + ", ||a||1=" + scale + ")");
            }
            swapRows(lu, col, pivot);
            swapRows(x, col, pivot);
            for (int row = col + 1; row < n; row++) {
                double factor = lu[row][col] / lu[col][col];
                if (factor == 0.0) {
                    continue;
                }
                for (int j = col; j < n; j++) {
                    lu[row][j] -= factor * lu[col][j];
                }
                for (int j = 0; j < m; j++) {
                    x[row][j] -= factor * x[col][j];
                }
            }
        }
        for (int row = n - 1; row >= 0; row--) {
            for (int j = 0; j < m; j++) {
                double sum = x[row][j];
                for (int k = row + 1; k < n; k++) {
                    sum -= lu[row][k] * x[k][j];
                }
                x[row][j] = sum / lu[row][row];
            }
        }
        return x;
    }

    /**
     * The inverse of a square, non-singular matrix.
     *
     * @param a an n×n matrix
     * @return a⁻¹, n×n
     * @throws IllegalArgumentException if {@code a} is not square or is singular to working
     *                                  precision
     */
    public static double[][] inverse(double[][] a) {
        return solve(a, identity(a.length));
    }

    /**
     * A readable multi-line rendering, for logs and test messages.
     *
     * @param a a matrix
     * @return one line per row, each ending with a newline
     */
    public static String toString(double[][] a) {
        StringBuilder text = new StringBuilder();
        for (double[] row : a) {
            text.append(Arrays.toString(row)).append('\n');
        }
        return text.toString();
    }

    private static void swapRows(double[][] a, int i, int j) {
        if (i != j) {
            double[] tmp = a[i];
            a[i] = a[j];
            a[j] = tmp;
        }
    }

    private static void requireShape(boolean ok, String operation, double[][] a, double[][] b) {
        if (!ok) {
            throw new IllegalArgumentException("cannot " + operation + " a " + a.length + "x"
                    + a[0].length + " matrix with a " + b.length + "x" + b[0].length + " matrix");
        }
    }
}
