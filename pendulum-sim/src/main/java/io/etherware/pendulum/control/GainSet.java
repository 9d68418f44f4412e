package io.etherware.pendulum.control;

import io.etherware.pendulum.linalg.Complex;
import io.etherware.pendulum.plant.LinearModel;
import io.etherware.pendulum.plant.PendulumParameters;
import java.util.List;
import java.util.Objects;

/**
 * A full-state feedback gain {@code K = [k_θ1, k_θ̇1, k_θ2, k_θ̇2]} for {@code u = −K (x − x0)},
 * named and versioned so a controller upgrade (paper Section VI-C1, Fig. 11) can say which one
 * runs, with the continuous-time poles it was designed for.
 *
 * <p>Two designs are provided: {@link #v1Soft} and {@link #v2Tight}, deliberately different
 * (the paper's Fig. 11 upgrade swaps a softer controller for a tighter one). Immutable value;
 * thread-safe.
 *
 * @param name a short name, e.g. {@code "V1-soft"}
 * @param version the gain version carried in controller state
 * @param polesRadPerS the continuous-time closed-loop poles the gain places
 * @param kTheta1NmPerRad gain on the arm angle error
 * @param kTheta1RateNmsPerRad gain on the arm rate
 * @param kTheta2NmPerRad gain on the pendulum angle
 * @param kTheta2RateNmsPerRad gain on the pendulum rate
 */
public record GainSet(
        String name,
        int version,
        List<Complex> polesRadPerS,
        double kTheta1NmPerRad,
        double kTheta1RateNmsPerRad,
        double kTheta2NmPerRad,
        double kTheta2RateNmsPerRad) {

    /**
     * V1 "soft": the pendulum modes (−9, −11 rad/s) just beyond the unstable pole (+7.97 rad/s),
     * a slow, lightly damped arm recentring (−2 ± 1.5j rad/s, about 2 s).
     */
    public static final List<Complex> V1_POLES = List.of(
            new Complex(-2.0, 1.5), new Complex(-2.0, -1.5),
            Complex.real(-9.0), Complex.real(-11.0));

    /**
     * V2 "tight": slightly faster pendulum modes (−10, −12 rad/s) and an arm recentring 2.5 times
     * faster and better damped (−5 ± 2j rad/s), with 5.6 times V1's arm-angle gain. Kept below
     * −12 rad/s so the loop is still stable when a 15 ms cycle is lost and the torque is held for
     * 30 ms (a faster set, e.g. −14/−18 rad/s, is not: spectral radius 1.07).
     */
    public static final List<Complex> V2_POLES = List.of(
            new Complex(-5.0, 2.0), new Complex(-5.0, -2.0),
            Complex.real(-10.0), Complex.real(-12.0));

    /**
     * Validates the name and that the gains are finite; keeps an unmodifiable copy of the poles.
     *
     * @throws NullPointerException     when {@code name} or {@code polesRadPerS} is null
     * @throws IllegalArgumentException when a gain is not finite
     */
    public GainSet {
        Objects.requireNonNull(name, "name");
        polesRadPerS = List.copyOf(polesRadPerS);
        for (double k : new double[] {kTheta1NmPerRad, kTheta1RateNmsPerRad, kTheta2NmPerRad,
                kTheta2RateNmsPerRad}) {
            if (!Double.isFinite(k)) {
                throw new IllegalArgumentException("gain set " + name + " has a non-finite gain " + k);
            }
        }
    }

    /**
     * A gain placing the poles of {@code A − B K} at the given poles (Ackermann).
     *
     * @param name         a short name, e.g. {@code "V1-soft"}
     * @param version      the gain version carried in controller state
     * @param model        the 4-state linear model to design for
     * @param polesRadPerS 4 continuous-time poles in rad/s; complex ones in conjugate pairs
     * @return the gain set
     * @throws IllegalArgumentException when the poles are not 4 or not closed under conjugation,
     *                                  or the model is not controllable
     */
    public static GainSet design(String name, int version, LinearModel model,
            List<Complex> polesRadPerS) {
        double[] k = Ackermann.gain(model.a(), model.b(), polesRadPerS);
        return new GainSet(name, version, polesRadPerS, k[0], k[1], k[2], k[3]);
    }

    /**
     * V1 "soft" ({@link #V1_POLES}) for the given pendulum, version 1.
     *
     * @param parameters the pendulum to design for
     * @return the gain set, named {@code V1-soft}
     */
    public static GainSet v1Soft(PendulumParameters parameters) {
        return design("V1-soft", 1, LinearModel.linearize(parameters, 0.0), V1_POLES);
    }

    /**
     * V2 "tight" ({@link #V2_POLES}) for the given pendulum, version 2.
     *
     * @param parameters the pendulum to design for
     * @return the gain set, named {@code V2-tight}
     */
    public static GainSet v2Tight(PendulumParameters parameters) {
        return design("V2-tight", 2, LinearModel.linearize(parameters, 0.0), V2_POLES);
    }

    /**
     * K as an array; allocates.
     *
     * @return a new array {@code [k_θ1, k_θ̇1, k_θ2, k_θ̇2]}, in N·m/rad and N·m·s/rad
     */
    public double[] gains() {
        return new double[] {kTheta1NmPerRad, kTheta1RateNmsPerRad, kTheta2NmPerRad,
                kTheta2RateNmsPerRad};
    }
}
