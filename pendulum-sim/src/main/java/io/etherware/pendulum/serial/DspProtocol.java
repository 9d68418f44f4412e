package io.etherware.pendulum.serial;

/**
 * The binary serial protocol between a controller host and the DSP board (see
 * {@code pendulum-sim/SERIAL-PROTOCOL.md}): frame layout, message types, payload sizes and the
 * big-endian field codecs.
 *
 * <pre>
 * frame = START(0xA5) TYPE(u8) LENGTH(u8) PAYLOAD(LENGTH bytes) CRC16(u16, big-endian)
 * CRC-16/CCITT-FALSE over TYPE, LENGTH and PAYLOAD
 * </pre>
 *
 * Every request carries a 16-bit sequence number that its reply echoes. Stateless and
 * thread-safe; the encoders write into caller-provided buffers and allocate nothing.
 */
public final class DspProtocol {

    /** The start-of-frame byte. */
    public static final int START = 0xA5;
    /** START, TYPE, LENGTH before the payload. */
    public static final int HEADER_BYTES = 3;
    /** The CRC after the payload. */
    public static final int CRC_BYTES = 2;
    /** Bytes of framing around a payload. */
    public static final int OVERHEAD_BYTES = HEADER_BYTES + CRC_BYTES;
    /** The largest payload of any message. */
    public static final int MAX_PAYLOAD_BYTES = 35;
    /** The largest frame. */
    public static final int MAX_FRAME_BYTES = OVERHEAD_BYTES + MAX_PAYLOAD_BYTES;

    /** Host → board: sample the encoders. Payload: sequence u16. */
    public static final int READ_ANGLES = 0x01;
    /** Host → board: set the motor torque. Payload: sequence u16, torque i32 in µN·m. */
    public static final int SET_TORQUE = 0x02;
    /** Host → board: report status. Payload: sequence u16. */
    public static final int READ_STATUS = 0x03;
    /** Board → host: sequence u16, encoder 1 i32 counts, encoder 2 i32 counts, time u32 µs. */
    public static final int ANGLES = 0x81;
    /** Board → host: sequence u16, flags u8 ({@link #ACK_FAULT_WATCHDOG}, {@link #ACK_SATURATED}). */
    public static final int ACK = 0x82;
    /** Board → host: see {@link BoardStatus} for the 35-byte layout. */
    public static final int STATUS = 0x83;

    /** Payload size of READ_ANGLES. */
    public static final int READ_ANGLES_BYTES = 2;
    /** Payload size of SET_TORQUE. */
    public static final int SET_TORQUE_BYTES = 6;
    /** Payload size of READ_STATUS. */
    public static final int READ_STATUS_BYTES = 2;
    /** Payload size of ANGLES. */
    public static final int ANGLES_BYTES = 14;
    /** Payload size of ACK. */
    public static final int ACK_BYTES = 3;
    /** Payload size of STATUS. */
    public static final int STATUS_BYTES = 35;

    /** Fault flag: the watchdog has cut the motor (no command within its timeout). */
    public static final int FAULT_WATCHDOG = 0x01;
    /** ACK flag: the watchdog fault was active when this command arrived (and is now cleared). */
    public static final int ACK_FAULT_WATCHDOG = 0x01;
    /** ACK flag: the commanded torque was beyond the motor's range and was clamped. */
    public static final int ACK_SATURATED = 0x02;

    /** Torque units on the wire: micro-newton-metres. */
    public static final double MICRO_NEWTON_METRES_PER_NM = 1e6;

    private DspProtocol() {}

    /**
     * The payload size of a message type.
     *
     * @param type a message type, e.g. {@link #READ_ANGLES}
     * @return the payload size in bytes; -1 for an unknown type
     */
    public static int payloadBytes(int type) {
        return switch (type) {
            case READ_ANGLES -> READ_ANGLES_BYTES;
            case SET_TORQUE -> SET_TORQUE_BYTES;
            case READ_STATUS -> READ_STATUS_BYTES;
            case ANGLES -> ANGLES_BYTES;
            case ACK -> ACK_BYTES;
            case STATUS -> STATUS_BYTES;
            default -> -1;
        };
    }

    /**
     * A readable name of a message type, for errors and logs.
     *
     * @param type a message type
     * @return e.g. {@code READ_ANGLES}; {@code 0x7F} for an unknown type
     */
    public static String typeName(int type) {
        return switch (type) {
            case READ_ANGLES -> "READ_ANGLES";
            case SET_TORQUE -> "SET_TORQUE";
            case READ_STATUS -> "READ_STATUS";
            case ANGLES -> "ANGLES";
            case ACK -> "ACK";
            case STATUS -> "STATUS";
            default -> String.format("0x%02X", type);
        };
    }

    /**
     * Frames a payload already written at {@code frame[HEADER_BYTES ...]}: writes the header and
     * the CRC around it.
     *
     * @param frame         the frame buffer, at least {@code OVERHEAD_BYTES + payloadLength} bytes
     * @param type          the message type
     * @param payloadLength the payload's length in bytes, within [0, {@value #MAX_PAYLOAD_BYTES}]
     * @return the frame length, in bytes
     * @throws IllegalArgumentException when {@code payloadLength} is out of range
     */
    public static int seal(byte[] frame, int type, int payloadLength) {
        if (payloadLength < 0 || payloadLength > MAX_PAYLOAD_BYTES) {
            throw new IllegalArgumentException("payloadLength=" + payloadLength + ": must be within [0, "
                    + MAX_PAYLOAD_BYTES + "]");
        }
        frame[0] = (byte) START;
        frame[1] = (byte) type;
        frame[2] = (byte) payloadLength;
        int crc = Crc16.of(frame, 1, 2 + payloadLength);
        putU16(frame, HEADER_BYTES + payloadLength, crc);
        return OVERHEAD_BYTES + payloadLength;
    }

    /**
     * Writes a request that carries only a sequence (READ_ANGLES, READ_STATUS).
     *
     * @param frame    the frame buffer, at least {@value #OVERHEAD_BYTES} + 2 bytes
     * @param type     {@link #READ_ANGLES} or {@link #READ_STATUS}
     * @param sequence the request's sequence number; its low 16 bits are sent
     * @return the frame length, in bytes
     */
    public static int encodeRequest(byte[] frame, int type, int sequence) {
        putU16(frame, HEADER_BYTES, sequence);
        return seal(frame, type, 2);
    }

    /**
     * Writes a SET_TORQUE frame.
     *
     * @param frame    the frame buffer, at least {@value #OVERHEAD_BYTES} + {@value #SET_TORQUE_BYTES} bytes
     * @param sequence the request's sequence number; its low 16 bits are sent
     * @param torqueNm the torque to apply, in N·m (see {@link #torqueToWire})
     * @return the frame length, in bytes
     */
    public static int encodeSetTorque(byte[] frame, int sequence, double torqueNm) {
        putU16(frame, HEADER_BYTES, sequence);
        putI32(frame, HEADER_BYTES + 2, torqueToWire(torqueNm));
        return seal(frame, SET_TORQUE, SET_TORQUE_BYTES);
    }

    /**
     * Writes an ANGLES frame.
     *
     * @param frame          the frame buffer, at least {@value #OVERHEAD_BYTES} + {@value #ANGLES_BYTES} bytes
     * @param sequence       the request's sequence number, echoed; its low 16 bits are sent
     * @param encoder1Counts joint-1 (arm) encoder count, multi-turn
     * @param encoder2Counts joint-2 (pendulum) encoder count, multi-turn, 0 upright
     * @param dspTimeUs      the board's time of the sample in µs; its low 32 bits are sent
     * @return the frame length, in bytes
     */
    public static int encodeAngles(byte[] frame, int sequence, int encoder1Counts,
            int encoder2Counts, long dspTimeUs) {
        putU16(frame, HEADER_BYTES, sequence);
        putI32(frame, HEADER_BYTES + 2, encoder1Counts);
        putI32(frame, HEADER_BYTES + 6, encoder2Counts);
        putI32(frame, HEADER_BYTES + 10, (int) dspTimeUs);
        return seal(frame, ANGLES, ANGLES_BYTES);
    }

    /**
     * Writes an ACK frame.
     *
     * @param frame    the frame buffer, at least {@value #OVERHEAD_BYTES} + {@value #ACK_BYTES} bytes
     * @param sequence the command's sequence number, echoed; its low 16 bits are sent
     * @param flags    {@link #ACK_FAULT_WATCHDOG} and {@link #ACK_SATURATED}, or 0
     * @return the frame length, in bytes
     */
    public static int encodeAck(byte[] frame, int sequence, int flags) {
        putU16(frame, HEADER_BYTES, sequence);
        frame[HEADER_BYTES + 2] = (byte) flags;
        return seal(frame, ACK, ACK_BYTES);
    }

    /**
     * Torque on the wire.
     *
     * @param torqueNm a torque, in N·m
     * @return µN·m, rounded, saturated to the i32 range (about ±2147 N·m); 0 for NaN
     */
    public static int torqueToWire(double torqueNm) {
        double micro = Math.rint(torqueNm * MICRO_NEWTON_METRES_PER_NM);
        if (Double.isNaN(micro)) {
            return 0;
        }
        return (int) Math.max(Integer.MIN_VALUE, Math.min(Integer.MAX_VALUE, micro));
    }

    /**
     * Torque from the wire.
     *
     * @param microNewtonMetres the wire value, in µN·m
     * @return the torque, in N·m
     */
    public static double torqueFromWire(int microNewtonMetres) {
        return microNewtonMetres / MICRO_NEWTON_METRES_PER_NM;
    }

    /**
     * Big-endian unsigned 16-bit write.
     *
     * @param buffer the destination, at least {@code offset + 2} bytes
     * @param offset where the high byte goes
     * @param value  the value; its low 16 bits are written
     */
    public static void putU16(byte[] buffer, int offset, int value) {
        buffer[offset] = (byte) (value >>> 8);
        buffer[offset + 1] = (byte) value;
    }

    /**
     * Big-endian 32-bit write.
     *
     * @param buffer the destination, at least {@code offset + 4} bytes
     * @param offset where the highest byte goes
     * @param value  the value, signed or an unsigned u32's low bits
     */
    public static void putI32(byte[] buffer, int offset, int value) {
        buffer[offset] = (byte) (value >>> 24);
        buffer[offset + 1] = (byte) (value >>> 16);
        buffer[offset + 2] = (byte) (value >>> 8);
        buffer[offset + 3] = (byte) value;
    }

    /**
     * Big-endian unsigned 16-bit read.
     *
     * @param buffer the source, at least {@code offset + 2} bytes
     * @param offset where the high byte is
     * @return the value, in [0, 65535]
     */
    public static int getU16(byte[] buffer, int offset) {
        return ((buffer[offset] & 0xFF) << 8) | (buffer[offset + 1] & 0xFF);
    }

    /**
     * Big-endian signed 32-bit read.
     *
     * @param buffer the source, at least {@code offset + 4} bytes
     * @param offset where the highest byte is
     * @return the value, as a signed int
     */
    public static int getI32(byte[] buffer, int offset) {
        return ((buffer[offset] & 0xFF) << 24) | ((buffer[offset + 1] & 0xFF) << 16)
                | ((buffer[offset + 2] & 0xFF) << 8) | (buffer[offset + 3] & 0xFF);
    }

    /**
     * Big-endian unsigned 32-bit read.
     *
     * @param buffer the source, at least {@code offset + 4} bytes
     * @param offset where the highest byte is
     * @return the value, in [0, 2³² − 1]
     */
    public static long getU32(byte[] buffer, int offset) {
        return getI32(buffer, offset) & 0xFFFF_FFFFL;
    }
}
