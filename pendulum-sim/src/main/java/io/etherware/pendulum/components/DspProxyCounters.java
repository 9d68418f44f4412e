package io.etherware.pendulum.components;

import io.etherware.core.component.ComponentState;

/**
 * What a {@link DspProxy} has done: its counters, which are also its {@link ComponentState}, so a
 * restart from the last snapshot keeps counting. Registered as
 * {@value PendulumContents#DSP_PROXY_COUNTERS}. Immutable.
 *
 * @param angleReads {@link ReadAngles} requests served with a reading
 * @param torqueCommands {@link SetTorque} commands the board acknowledged
 * @param statusReads {@link StatusRequest}s answered
 * @param timeouts serial exchanges that got no reply within the client's attempts
 * @param linkErrors serial exchanges that failed because the link failed
 * @param saturatedCommands acknowledged commands the board clamped to its torque range
 * @param watchdogRecoveries acknowledged commands that re-enabled a motor cut by the watchdog
 * @param unexpectedMessages messages of a contents type the proxy does not serve
 * @param lastTorqueNm the last torque the board acknowledged
 */
public record DspProxyCounters(
        long angleReads,
        long torqueCommands,
        long statusReads,
        long timeouts,
        long linkErrors,
        long saturatedCommands,
        long watchdogRecoveries,
        long unexpectedMessages,
        double lastTorqueNm) implements ComponentState {

    /** Nothing done yet. */
    public static final DspProxyCounters ZERO = new DspProxyCounters(0, 0, 0, 0, 0, 0, 0, 0, 0.0);

    /**
     * Serial exchanges that failed, timeouts and link errors.
     *
     * @return {@code timeouts + linkErrors}
     */
    public long serialFailures() {
        return timeouts + linkErrors;
    }
}
