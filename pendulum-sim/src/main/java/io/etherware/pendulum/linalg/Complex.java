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

    /** A real number. */
    public static Complex real(double re) {
        return new Complex(re, 0.0);
    }

    /** The modulus |z|. */
    public double abs() {
        return Math.hypot(re, im);
    }

    /** The complex conjugate. */
    public Complex conjugate() {
        return new Complex(re, -im);
    }

    /** {@code this + other}. */
    public Complex plus(Complex other) {
        return new Complex(re + other.re, im + other.im);
    }

    /** {@code this - other}. */
    public Complex minus(Complex other) {
        return new Complex(re - other.re, im - other.im);
    }

    /** {@code this * other}. */
    public Complex times(Complex other) {
        return new Complex(re * other.re - im * other.im, re * other.im + im * other.re);
    }

    /** {@code exp(this * t)}: maps a continuous-time pole to the z-plane for a sample time t. */
    public Complex expTimes(double t) {
        double magnitude = Math.exp(re * t);
        return new Complex(magnitude * Math.cos(im * t), magnitude * Math.sin(im * t));
    }

    /** Whether the imaginary part is zero within {@code tolerance} relative to the modulus. */
    public boolean isReal(double tolerance) {
        return Math.abs(im) <= tolerance * Math.max(1.0, abs());
    }

    @Override
    public String toString() {
        if (im == 0.0) {
            return String.format("%.6g", re);
        }
        return String.format("%.6g%s%.6gi", re, im < 0 ? "-" : "+", Math.abs(im));
    }
}
