package io.etherware.pendulum.control;

import java.util.Objects;

/**
 * One control cycle of the paper's balancing controller, free of any middleware: from the two
 * encoder angles and the board's time stamp to the motor torque, through the
 * {@link VelocityEstimator} and the saturated {@link StateFeedbackLaw}.
 *
 * <p>It only ever sees what the DSP board reports (design decision 9): never the simulation.
 * Not thread-safe: one controller owns it and calls it once per cycle. Its memory is a
 * {@link BalanceControlState} record.
 */
public final class BalanceControl {

    private final double maxTorqueNm;
    private final VelocityEstimator estimator;
    private StateFeedbackLaw law;
    private long cycles;
    private long saturatedCycles;

    /**
     * A controller.
     *
     * @param gains the initial gain set
     * @param theta1ReferenceRad θ1r, the arm set point
     * @param maxTorqueNm the torque limit the law clamps to
     * @param filterTimeConstantNs the velocity filter's τ (see {@link VelocityEstimator})
     */
    public BalanceControl(GainSet gains, double theta1ReferenceRad, double maxTorqueNm,
            long filterTimeConstantNs) {
        this.maxTorqueNm = maxTorqueNm;
        this.law = new StateFeedbackLaw(gains, theta1ReferenceRad, maxTorqueNm);
        this.estimator = new VelocityEstimator(filterTimeConstantNs,
                VelocityEstimator.DEFAULT_MAX_GAP_NS);
    }

    /**
     * Computes the torque for one sample.
     *
     * @param theta1Rad θ1 as measured by encoder 1
     * @param theta2Rad θ2 as measured by encoder 2
     * @param dspTimeUs the board's time stamp of the sample, µs, unwrapped
     * @return the torque to command, within ±maxTorqueNm
     */
    public double update(double theta1Rad, double theta2Rad, long dspTimeUs) {
        VelocityEstimatorState memory = estimator.update(theta1Rad, theta2Rad, dspTimeUs);
        double unsaturated = law.unsaturatedTorqueNm(theta1Rad, memory.theta1RateRadPerS(),
                theta2Rad, memory.theta2RateRadPerS());
        double torque = StateFeedbackLaw.clamp(unsaturated, maxTorqueNm);
        cycles++;
        if (torque != unsaturated) {
            saturatedCycles++;
        }
        return torque;
    }

    /**
     * Switches to another gain set from the next cycle on, keeping the estimator's memory and the
     * arm set point.
     *
     * @param gains the new gain set
     */
    public void useGains(GainSet gains) {
        this.law = new StateFeedbackLaw(gains, law.theta1ReferenceRad(), maxTorqueNm);
    }

    /**
     * The current memory, for a controller to carry through an upgrade or a migration.
     *
     * @return a new snapshot of the gains, set point, estimator memory and counters
     */
    public BalanceControlState state() {
        return new BalanceControlState(law.gains(), law.theta1ReferenceRad(), estimator.state(),
                cycles, saturatedCycles);
    }

    /**
     * Continues from a memory carried over from another instance; the torque limit stays this
     * instance's.
     *
     * @param memory a memory from {@link #state()}
     * @throws NullPointerException when {@code memory} is null
     */
    public void restore(BalanceControlState memory) {
        Objects.requireNonNull(memory, "memory");
        this.law = new StateFeedbackLaw(memory.gains(), memory.theta1ReferenceRad(), maxTorqueNm);
        this.estimator.restore(memory.estimator());
        this.cycles = memory.cycles();
        this.saturatedCycles = memory.saturatedCycles();
    }

    /**
     * The law in use.
     *
     * @return the law with the current gains, set point and torque limit
     */
    public StateFeedbackLaw law() {
        return law;
    }
}
