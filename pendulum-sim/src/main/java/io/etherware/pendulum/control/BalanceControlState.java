package io.etherware.pendulum.control;

import java.util.Objects;

/**
 * Everything a {@link BalanceControl} remembers between cycles: the gain in use, the arm set
 * point, the estimator's memory and counters. A plain record, so the future PendulumController
 * component can carry it as its ComponentState through an upgrade or a migration. Immutable;
 * thread-safe.
 *
 * @param gains the gain set in use
 * @param theta1ReferenceRad θ1r
 * @param estimator the velocity estimator's memory
 * @param cycles control updates computed
 * @param saturatedCycles updates whose torque was clamped
 */
public record BalanceControlState(
        GainSet gains,
        double theta1ReferenceRad,
        VelocityEstimatorState estimator,
        long cycles,
        long saturatedCycles) {

    /** Rejects nulls. */
    public BalanceControlState {
        Objects.requireNonNull(gains, "gains");
        Objects.requireNonNull(estimator, "estimator");
    }
}
