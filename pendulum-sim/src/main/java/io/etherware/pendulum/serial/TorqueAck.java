package io.etherware.pendulum.serial;

/**
 * The board's acknowledgement of a SET_TORQUE. Immutable value; thread-safe.
 *
 * @param sequence the command's sequence number, echoed
 * @param flags {@link DspProtocol#ACK_FAULT_WATCHDOG} and {@link DspProtocol#ACK_SATURATED}
 */
public record TorqueAck(int sequence, int flags) {

    /**
     * Whether the watchdog had cut the motor before this command re-enabled it.
     *
     * @return true when {@link DspProtocol#ACK_FAULT_WATCHDOG} is set
     */
    public boolean watchdogWasTripped() {
        return (flags & DspProtocol.ACK_FAULT_WATCHDOG) != 0;
    }

    /**
     * Whether the command exceeded the motor's torque range and was clamped.
     *
     * @return true when {@link DspProtocol#ACK_SATURATED} is set
     */
    public boolean saturated() {
        return (flags & DspProtocol.ACK_SATURATED) != 0;
    }
}
