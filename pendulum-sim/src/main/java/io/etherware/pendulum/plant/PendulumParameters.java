package io.etherware.pendulum.plant;

/**
 * Physical parameters of the rotary (Furuta) inverted pendulum of the paper's Section VI-A,
 * equation (1), after Iwashiro, Furuta and Åström [13].
 *
 * <p>Link 1 (the arm) turns in the horizontal plane about joint 1, driven by the DC motor; link 2
 * (the pendulum) swings about joint 2 at the arm's tip. {@code θ2 = 0} is upright. The paper
 * gives {@code m = 0.2 kg}, {@code l1 = 8 cm} and {@code l2 = 20 cm}; the values of {@code J1} and
 * {@code J2} were lost from its text, so the defaults below are chosen to be physically plausible:
 *
 * <ul>
 *   <li>{@code J2 = m (2 l2)² / 12 = 2.667e-3 kg·m²}: the pendulum as a uniform rod of mass
 *       {@code m} and length {@code 2 l2 = 0.4 m}, whose centre of mass is then at {@code l2}
 *       from joint 2, taken about that centre of mass as the paper defines {@code J_i}.
 *   <li>{@code J1 = 1.0e-3 kg·m²}: equation (1) has no {@code m1 lc1²} term, so the arm's own centre
 *       of mass lies on the joint-1 axis (a counter-balanced arm) and "about its centre of mass" is
 *       about joint 1. A balanced aluminium arm of about 0.15 kg and 0.24 m gives
 *       {@code 0.15 · 0.24² / 12 ≈ 7e-4 kg·m²}; the motor rotor, hub and encoder disc add about
 *       {@code 3e-4 kg·m²}. The pendulum's mass at the arm tip is the separate {@code m l1²} term.
 * </ul>
 *
 * <p>Viscous friction is optional (zero by default, as in equation (1)). Immutable; validated at
 * construction; thread-safe.
 *
 * @param pendulumMassKg m, the pendulum's mass
 * @param armLengthM l1, from joint 1 to joint 2
 * @param pendulumCenterOfMassM l2, from joint 2 to the pendulum's centre of mass
 * @param armInertiaKgM2 J1, everything turning with joint 1, about the joint-1 axis
 * @param pendulumInertiaKgM2 J2, the pendulum about its own centre of mass
 * @param armDampingNmsPerRad b1, viscous friction at joint 1 (0 for none)
 * @param pendulumDampingNmsPerRad b2, viscous friction at joint 2 (0 for none)
 * @param gravityMPerS2 g
 */
public record PendulumParameters(
        double pendulumMassKg,
        double armLengthM,
        double pendulumCenterOfMassM,
        double armInertiaKgM2,
        double pendulumInertiaKgM2,
        double armDampingNmsPerRad,
        double pendulumDampingNmsPerRad,
        double gravityMPerS2) {

    /** The paper's m = 0.2 kg. */
    public static final double DEFAULT_MASS_KG = 0.2;
    /** The paper's l1 = 8 cm. */
    public static final double DEFAULT_ARM_LENGTH_M = 0.08;
    /** The paper's l2 = 20 cm. */
    public static final double DEFAULT_CENTER_OF_MASS_M = 0.20;
    /** Chosen J1: balanced arm plus rotor, hub and encoder (see the type's Javadoc). */
    public static final double DEFAULT_ARM_INERTIA_KG_M2 = 1.0e-3;
    /** Chosen J2: a uniform 0.4 m rod of mass m about its centre (see the type's Javadoc). */
    public static final double DEFAULT_PENDULUM_INERTIA_KG_M2 =
            DEFAULT_MASS_KG * (2 * DEFAULT_CENTER_OF_MASS_M) * (2 * DEFAULT_CENTER_OF_MASS_M) / 12.0;
    /** Standard gravity. */
    public static final double STANDARD_GRAVITY_M_PER_S2 = 9.80665;

    /**
     * Validates every field; the message names the field, its value and what is allowed.
     *
     * @throws IllegalArgumentException when a mass, length, inertia or the gravity is not finite
     *                                  and positive, or a damping is not finite and 0 or more
     */
    public PendulumParameters {
        requirePositive("pendulumMassKg", pendulumMassKg);
        requirePositive("armLengthM", armLengthM);
        requirePositive("pendulumCenterOfMassM", pendulumCenterOfMassM);
        requirePositive("armInertiaKgM2", armInertiaKgM2);
        requirePositive("pendulumInertiaKgM2", pendulumInertiaKgM2);
        requireNonNegative("armDampingNmsPerRad", armDampingNmsPerRad);
        requireNonNegative("pendulumDampingNmsPerRad", pendulumDampingNmsPerRad);
        requirePositive("gravityMPerS2", gravityMPerS2);
    }

    /**
     * The paper's masses and lengths, the chosen J1 and J2, no friction, standard gravity.
     *
     * @return the default parameters
     */
    public static PendulumParameters defaults() {
        return new PendulumParameters(DEFAULT_MASS_KG, DEFAULT_ARM_LENGTH_M,
                DEFAULT_CENTER_OF_MASS_M, DEFAULT_ARM_INERTIA_KG_M2,
                DEFAULT_PENDULUM_INERTIA_KG_M2, 0.0, 0.0, STANDARD_GRAVITY_M_PER_S2);
    }

    /**
     * A copy with viscous friction at both joints.
     *
     * @param armNmsPerRad      b1 at joint 1, in N·m·s/rad, finite and 0 or more
     * @param pendulumNmsPerRad b2 at joint 2, in N·m·s/rad, finite and 0 or more
     * @return the copy
     * @throws IllegalArgumentException when a damping is out of range
     */
    public PendulumParameters withDamping(double armNmsPerRad, double pendulumNmsPerRad) {
        return new PendulumParameters(pendulumMassKg, armLengthM, pendulumCenterOfMassM,
                armInertiaKgM2, pendulumInertiaKgM2, armNmsPerRad, pendulumNmsPerRad, gravityMPerS2);
    }

    /**
     * A copy with other inertias J1 and J2.
     *
     * @param armKgM2      J1, about the joint-1 axis, in kg·m², finite and positive
     * @param pendulumKgM2 J2, about the pendulum's centre of mass, in kg·m², finite and positive
     * @return the copy
     * @throws IllegalArgumentException when an inertia is out of range
     */
    public PendulumParameters withInertias(double armKgM2, double pendulumKgM2) {
        return new PendulumParameters(pendulumMassKg, armLengthM, pendulumCenterOfMassM,
                armKgM2, pendulumKgM2, armDampingNmsPerRad, pendulumDampingNmsPerRad, gravityMPerS2);
    }

    /**
     * A copy with other mass and lengths m, l1, l2 (inertias unchanged).
     *
     * @param massKg        m, in kg, finite and positive
     * @param armM          l1, in m, finite and positive
     * @param centerOfMassM l2, in m, finite and positive
     * @return the copy
     * @throws IllegalArgumentException when a value is out of range
     */
    public PendulumParameters withMassAndLengths(double massKg, double armM, double centerOfMassM) {
        return new PendulumParameters(massKg, armM, centerOfMassM, armInertiaKgM2,
                pendulumInertiaKgM2, armDampingNmsPerRad, pendulumDampingNmsPerRad, gravityMPerS2);
    }

    /**
     * A copy with another gravity.
     *
     * @param metresPerS2 g, in m/s², finite and positive
     * @return the copy
     * @throws IllegalArgumentException when {@code metresPerS2} is out of range
     */
    public PendulumParameters withGravity(double metresPerS2) {
        return new PendulumParameters(pendulumMassKg, armLengthM, pendulumCenterOfMassM,
                armInertiaKgM2, pendulumInertiaKgM2, armDampingNmsPerRad,
                pendulumDampingNmsPerRad, metresPerS2);
    }

    private static void requirePositive(String field, double value) {
        if (!(value > 0.0) || !Double.isFinite(value)) {
            throw new IllegalArgumentException(field + "=" + value + ": must be finite and > 0");
        }
    }

    private static void requireNonNegative(String field, double value) {
        if (!(value >= 0.0) || !Double.isFinite(value)) {
            throw new IllegalArgumentException(field + "=" + value
                    + ": must be finite and >= 0 (0 means no friction)");
        }
    }
}
