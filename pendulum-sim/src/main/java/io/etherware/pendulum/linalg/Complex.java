package io.etherware.pendulum.linalg;

/**
 * A complex number, as the eigenvalue and pole routines need it.
 *
 * <p>Immutable value; safe to share between threads.
 *
 * @param re real part
 * @param im imaginary part
 */
public record Complex(double re, double im) {

    /**
     * A real number.
     *
     * @param re the value
     * @return {@code re + 0i}
     */
    public static Complex real(double re) {
        return new Complex(re, 0.0);
    }

    /**
     * The modulus |z|.
     *
     * @return {@code sqrt(re² + im²)}, without intermediate overflow
     */
    public double abs() {
        return Math.hypot(re, im);
    }

    /**
     * The complex conjugate.
     *
     * @return {@code re - im i}
     */
    public Complex conjugate() {
        return new Complex(re, -im);
    }

    /**
     * The sum.
     *
     * @param other the other addend
     * @return {@code this + other}
     */
    public Complex plus(Complex other) {
        return new Complex(re + other.re, im + other.im);
    }

    /**
     * The difference.
     *
     * @param other the subtrahend
     * @return {@code this - other}
     */
    public Complex minus(Complex other) {
        return new Complex(re - other.re, im - other.im);
    }

    /**
     * The product.
     *
     * @param other the other factor
     * @return {@code this * other}
     */
    public Complex times(Complex other) {
        return new Complex(re * other.re - im * other.im, re * other.im + im * other.re);
    }

    /**
     * Maps a continuous-time pole to the z-plane for a sample time.
     *
     * @param t the sample time, in the reciprocal unit of this number (seconds for a pole in rad/s)
     * @return {@code exp(this * t)}
     */
    public Complex expTimes(double t) {
        double magnitude = Math.exp(re * t);
        return new Complex(magnitude * Math.cos(im * t), magnitude * Math.sin(im * t));
    }

    /**
     * Whether this is real to within a tolerance.
     *
     * @param tolerance the largest {@code |im|} taken as zero, relative to the modulus (absolute
     *                  below a modulus of 1), e.g. {@code 1e-9}
     * @return true when {@code |im| <= tolerance * max(1, |z|)}
     */
    public boolean isReal(double tolerance) {
        return Math.abs(im) <= tolerance * Math.max(1.0, abs());
    }

    /** {@code re}, or {@code re±imi}, each to six significant digits, e.g. {@code -3.00000+4.00000i}. */
    @Override
    public String toString() {
        if (im == 0.0) {
            return String.format("%.6g", re);
        }
        return String.format("%.6g%s%.6gi", re, im < 0 ? "-" : "+", Math.abs(im));
    }
}
