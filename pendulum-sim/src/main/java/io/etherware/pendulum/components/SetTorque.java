package io.etherware.pendulum.components;

import io.etherware.core.message.Contents;

/**
 * A motor command to the {@link DspProxy}: sent, not requested. The proxy forwards it to the
 * board and waits for the board's ACK itself; saturation, watchdog recoveries and serial failures
 * show in its counters ({@link StatusRequest}), not in a reply, so the control loop stays
 * request angles, reply, send torque (paper Section VI-A). Registered as
 * {@value PendulumContents#SET_TORQUE}. Immutable.
 *
 * @param cycle the control cycle that computed it (the Tick's sequence)
 * @param torqueNm the motor torque; the board clamps it to its range
 */
public record SetTorque(long cycle, double torqueNm) implements Contents {

    /** Rejects a non-finite torque: never command a NaN. */
    public SetTorque {
        if (!Double.isFinite(torqueNm)) {
            throw new IllegalArgumentException("torqueNm=" + torqueNm + ": must be finite");
        }
    }
}
