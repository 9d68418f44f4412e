package io.etherware.pendulum.control;

import java.util.Objects;

/**
 * Estimates the joint rates from successive encoder angles and their DSP time stamps: the
 * backward difference {@code (θ[k] − θ[k-1]) / (t[k] − t[k-1])} through a first-order low-pass
 * filter, {@code v += α (difference − v)} with {@code α = 1 − e^{−Δt/τ}}.
 *
 * <p>Using the board's own time stamps, not the controller's clock, keeps the estimate right when
 * a cycle is late or a reply is lost: the difference spans the real sampling interval. A sample
 * with the same time stamp as the last one is ignored; one whose time stamp goes backwards or
 * follows a gap longer than {@code maxGapNs} restarts the differences and keeps the previous rates.
 *
 * <p>Not thread-safe: owned by one controller. Its memory is a {@link VelocityEstimatorState}
 * record ({@link #state()}, {@link #restore}).
 */
public final class VelocityEstimator {

    /** Default filter time constant, 5 ms: about one encoder count of noise at a 1 ms period. */
    public static final long DEFAULT_FILTER_TIME_CONSTANT_NS = 5_000_000L;
    /** Default longest gap still differenced, 250 ms. */
    public static final long DEFAULT_MAX_GAP_NS = 250_000_000L;

    private final long filterTimeConstantNs;
    private final long maxGapUs;
    private VelocityEstimatorState state = VelocityEstimatorState.INITIAL;

    /** An estimator with the default filter and gap. */
    public VelocityEstimator() {
        this(DEFAULT_FILTER_TIME_CONSTANT_NS, DEFAULT_MAX_GAP_NS);
    }

    /**
     * An estimator.
     *
     * @param filterTimeConstantNs τ of the low-pass filter, 0 or more; 0 uses the raw differences
     * @param maxGapNs the longest interval between samples that is still differenced, at least
     *                 1000 (1 µs)
     * @throws IllegalArgumentException when a value is out of range
     */
    public VelocityEstimator(long filterTimeConstantNs, long maxGapNs) {
        if (filterTimeConstantNs < 0) {
            throw new IllegalArgumentException("filterTimeConstantNs=" + filterTimeConstantNs
                    + ": must be >= 0 (0 disables filtering)");
        }
        if (maxGapNs < 1_000L) {
            throw new IllegalArgumentException("maxGapNs=" + maxGapNs + ": must be >= 1000 (1 µs)");
        }
        this.filterTimeConstantNs = filterTimeConstantNs;
        this.maxGapUs = maxGapNs / 1_000L;
    }

    /**
     * The filter weight for an interval.
     *
     * @param intervalNs           Δt, in nanoseconds
     * @param filterTimeConstantNs τ, in nanoseconds; 0 for no filtering
     * @return α = 1 − e^{−Δt/τ}, in [0, 1]; 1 when τ = 0
     */
    public static double smoothing(long intervalNs, long filterTimeConstantNs) {
        if (filterTimeConstantNs == 0) {
            return 1.0;
        }
        return -Math.expm1(-(double) intervalNs / filterTimeConstantNs);
    }

    /**
     * Takes one sample and returns the updated memory, whose rates are the current estimate.
     * Allocates one small record per accepted sample.
     *
     * @param theta1Rad θ1 as measured by encoder 1
     * @param theta2Rad θ2 as measured by encoder 2
     * @param dspTimeUs the board's time stamp of the sample, µs, monotonic (already unwrapped)
     * @return the memory after the sample; the previous one when the time stamp repeats
     */
    public VelocityEstimatorState update(double theta1Rad, double theta2Rad, long dspTimeUs) {
        VelocityEstimatorState last = state;
        if (!last.primed()) {
            state = new VelocityEstimatorState(true, dspTimeUs, theta1Rad, theta2Rad,
                    last.theta1RateRadPerS(), last.theta2RateRadPerS(), last.samples() + 1,
                    last.discontinuities());
            return state;
        }
        long intervalUs = dspTimeUs - last.lastDspTimeUs();
        if (intervalUs == 0) {
            return last;
        }
        if (intervalUs < 0 || intervalUs > maxGapUs) {
            state = new VelocityEstimatorState(true, dspTimeUs, theta1Rad, theta2Rad,
                    last.theta1RateRadPerS(), last.theta2RateRadPerS(), last.samples() + 1,
                    last.discontinuities() + 1);
            return state;
        }
        double intervalS = intervalUs * 1e-6;
        double alpha = smoothing(intervalUs * 1_000L, filterTimeConstantNs);
        double rate1 = last.theta1RateRadPerS()
                + alpha * ((theta1Rad - last.lastTheta1Rad()) / intervalS - last.theta1RateRadPerS());
        double rate2 = last.theta2RateRadPerS()
                + alpha * ((theta2Rad - last.lastTheta2Rad()) / intervalS - last.theta2RateRadPerS());
        state = new VelocityEstimatorState(true, dspTimeUs, theta1Rad, theta2Rad, rate1, rate2,
                last.samples() + 1, last.discontinuities());
        return state;
    }

    /**
     * The current memory.
     *
     * @return the memory after the last sample; {@link VelocityEstimatorState#INITIAL} before any
     */
    public VelocityEstimatorState state() {
        return state;
    }

    /**
     * Continues from a memory carried over from another instance.
     *
     * @param memory a memory from {@link #state()}
     * @throws NullPointerException when {@code memory} is null
     */
    public void restore(VelocityEstimatorState memory) {
        this.state = Objects.requireNonNull(memory, "memory");
    }

    /**
     * τ of the low-pass filter.
     *
     * @return τ, in nanoseconds; 0 for raw differences
     */
    public long filterTimeConstantNs() {
        return filterTimeConstantNs;
    }
}
