package io.etherware.pendulum.components;

import io.etherware.core.component.ComponentState;
import io.etherware.pendulum.control.BalanceControlState;
import java.util.Objects;

/**
 * Everything a {@link PendulumController} carries through a restart, an upgrade or a migration
 * (paper Section VI-C): the control memory (gain set in use, θ1r, the velocity estimator's last
 * sample and filtered rates) and the loop's counters. Registered as
 * {@value PendulumContents#CONTROLLER_STATE}; travels as XML. Immutable.
 *
 * @param control the control memory: gains, θ1r, estimator, updates computed and saturated
 * @param ticks Ticks received
 * @param missedReplies cycles whose readout failed (timeout, undeliverable, {@link DspFault}):
 *     no torque was sent, the board held the last one
 * @param lateReplies readout outcomes that came after a newer Tick had abandoned their cycle;
 *     dropped
 * @param abandonedCycles Ticks that found the previous cycle still waiting for its reading: that
 *     cycle is abandoned, no torque comes from it and the board holds the last one for another
 *     period. Causes: a reading slower than the period, or a swap between request and reading
 * @param skippedTicks releases missing from the Tick sequence (gaps the ticker skipped)
 * @param lastTickSequence the sequence of the last Tick, or -1 before the first
 * @param pendingCycle the cycle waiting for its readout, or -1; a new instance that takes over a
 *     pending cycle counts it as abandoned at its first Tick, because the reply goes to the
 *     instance that asked
 * @param lastTorqueNm the last torque sent
 */
public record ControllerState(
        BalanceControlState control,
        long ticks,
        long missedReplies,
        long lateReplies,
        long abandonedCycles,
        long skippedTicks,
        long lastTickSequence,
        long pendingCycle,
        double lastTorqueNm) implements ComponentState {

    /** The layout version of this record (see {@link ComponentState#schemaVersion()}). */
    public static final int SCHEMA_VERSION = 1;

    /**
     * Rejects a missing control memory.
     *
     * @throws NullPointerException when {@code control} is null
     */
    public ControllerState {
        Objects.requireNonNull(control, "control");
    }

    /**
     * The layout version of this record, for an upgraded controller's restore.
     *
     * @return {@value #SCHEMA_VERSION}
     */
    @Override
    public int schemaVersion() {
        return SCHEMA_VERSION;
    }

    /**
     * Torque commands sent: one per control update.
     *
     * @return the control memory's update count
     */
    public long commands() {
        return control.cycles();
    }

    /**
     * The version of the gain set in use.
     *
     * @return the gain set's version, e.g. 1 for V1-soft
     */
    public int gainVersion() {
        return control.gains().version();
    }
}
