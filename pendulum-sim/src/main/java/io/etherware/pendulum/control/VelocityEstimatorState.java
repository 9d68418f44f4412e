package io.etherware.pendulum.control;

/**
 * The memory of a {@link VelocityEstimator}: the last sample and the filtered rates. A plain
 * record so a controller can carry it in its component state across an upgrade or migration.
 * Immutable; thread-safe.
 *
 * @param primed whether a first sample has been seen
 * @param lastDspTimeUs the DSP time stamp of the last accepted sample, µs
 * @param lastTheta1Rad θ1 of the last accepted sample
 * @param lastTheta2Rad θ2 of the last accepted sample
 * @param theta1RateRadPerS the filtered estimate of θ̇1
 * @param theta2RateRadPerS the filtered estimate of θ̇2
 * @param samples samples accepted
 * @param discontinuities samples that restarted the differences (time went backwards or a gap
 *     longer than the estimator's maximum); duplicates of the last time stamp are not counted
 */
public record VelocityEstimatorState(
        boolean primed,
        long lastDspTimeUs,
        double lastTheta1Rad,
        double lastTheta2Rad,
        double theta1RateRadPerS,
        double theta2RateRadPerS,
        long samples,
        long discontinuities) {

    /** Before the first sample. */
    public static final VelocityEstimatorState INITIAL =
            new VelocityEstimatorState(false, 0L, 0.0, 0.0, 0.0, 0.0, 0L, 0L);
}
