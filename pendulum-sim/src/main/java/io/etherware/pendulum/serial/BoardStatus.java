package io.etherware.pendulum.serial;

import static io.etherware.pendulum.serial.DspProtocol.HEADER_BYTES;

/**
 * The DSP board's fault flags and counters, as a STATUS reply carries them. Immutable value;
 * thread-safe.
 *
 * <p>Wire layout of the 35-byte STATUS payload, big-endian: sequence u16, faults u8,
 * dspTimeUs u32, framesAccepted u32, framesRejected u32, bytesDiscarded u32, watchdogTrips u32,
 * torqueCommands u32, appliedTorque i32 µN·m, countsPerRevolution u32. Counters wrap at 2³².
 *
 * @param faults fault flags ({@link DspProtocol#FAULT_WATCHDOG})
 * @param dspTimeUs the board's clock, µs (low 32 bits on the wire)
 * @param framesAccepted valid frames the board received
 * @param framesRejected candidate frames the board rejected (bad CRC, type or length)
 * @param bytesDiscarded bytes the board skipped while resynchronizing
 * @param watchdogTrips times the watchdog cut the motor
 * @param torqueCommands SET_TORQUE commands applied
 * @param appliedTorqueNm the torque the motor applies now
 * @param countsPerRevolution the encoders' resolution
 */
public record BoardStatus(
        int faults,
        long dspTimeUs,
        long framesAccepted,
        long framesRejected,
        long bytesDiscarded,
        long watchdogTrips,
        long torqueCommands,
        double appliedTorqueNm,
        int countsPerRevolution) {

    /**
     * Whether the watchdog has cut the motor and no command has arrived since.
     *
     * @return true when {@link DspProtocol#FAULT_WATCHDOG} is set
     */
    public boolean watchdogFault() {
        return (faults & DspProtocol.FAULT_WATCHDOG) != 0;
    }

    /**
     * Writes a STATUS frame answering a request; allocation-free.
     *
     * @param frame    the frame buffer, at least {@value DspProtocol#MAX_FRAME_BYTES} bytes
     * @param sequence the request's sequence number, echoed; its low 16 bits are sent
     * @return the frame length, in bytes
     */
    public int encode(byte[] frame, int sequence) {
        int at = HEADER_BYTES;
        DspProtocol.putU16(frame, at, sequence);
        frame[at + 2] = (byte) faults;
        DspProtocol.putI32(frame, at + 3, (int) dspTimeUs);
        DspProtocol.putI32(frame, at + 7, (int) framesAccepted);
        DspProtocol.putI32(frame, at + 11, (int) framesRejected);
        DspProtocol.putI32(frame, at + 15, (int) bytesDiscarded);
        DspProtocol.putI32(frame, at + 19, (int) watchdogTrips);
        DspProtocol.putI32(frame, at + 23, (int) torqueCommands);
        DspProtocol.putI32(frame, at + 27, DspProtocol.torqueToWire(appliedTorqueNm));
        DspProtocol.putI32(frame, at + 31, countsPerRevolution);
        return DspProtocol.seal(frame, DspProtocol.STATUS, DspProtocol.STATUS_BYTES);
    }

    /**
     * Reads a STATUS payload (after its sequence number check by the caller).
     *
     * @param payload the buffer holding a {@value DspProtocol#STATUS_BYTES}-byte STATUS payload
     * @param offset  where the payload starts
     * @return the status; counters are the wire's 32-bit values
     */
    public static BoardStatus decode(byte[] payload, int offset) {
        return new BoardStatus(
                payload[offset + 2] & 0xFF,
                DspProtocol.getU32(payload, offset + 3),
                DspProtocol.getU32(payload, offset + 7),
                DspProtocol.getU32(payload, offset + 11),
                DspProtocol.getU32(payload, offset + 15),
                DspProtocol.getU32(payload, offset + 19),
                DspProtocol.getU32(payload, offset + 23),
                DspProtocol.torqueFromWire(DspProtocol.getI32(payload, offset + 27)),
                DspProtocol.getI32(payload, offset + 31));
    }
}
