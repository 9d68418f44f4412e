package io.etherware.pendulum.serial;

/**
 * CRC-16/CCITT-FALSE: polynomial 0x1021, initial value 0xFFFF, no reflection, no final XOR
 * (the "CRC-16/IBM-3740" of the Greg Cook catalogue). Check value: {@code "123456789"} → 0x29B1.
 *
 * <p>It detects every single-, double- and odd-count bit error and every burst up to 16 bits in
 * our frames. Table-driven, allocation-free, stateless and thread-safe.
 */
public final class Crc16 {

    /** The initial register value. */
    public static final int INITIAL = 0xFFFF;

    private static final int POLYNOMIAL = 0x1021;
    private static final int[] TABLE = new int[256];

    static {
        for (int i = 0; i < 256; i++) {
            int crc = i << 8;
            for (int bit = 0; bit < 8; bit++) {
                crc = (crc & 0x8000) != 0 ? (crc << 1) ^ POLYNOMIAL : crc << 1;
            }
            TABLE[i] = crc & 0xFFFF;
        }
    }

    private Crc16() {}

    /**
     * The CRC of a byte range.
     *
     * @param data   the bytes
     * @param offset the first byte's index
     * @param length how many bytes, 0 or more
     * @return the CRC of {@code data[offset, offset + length)}, in [0, 0xFFFF]
     */
    public static int of(byte[] data, int offset, int length) {
        return update(INITIAL, data, offset, length);
    }

    /**
     * Continues a CRC over more bytes.
     *
     * @param crc    the CRC so far, {@link #INITIAL} to start
     * @param data   the bytes
     * @param offset the first byte's index
     * @param length how many bytes, 0 or more
     * @return the CRC including these bytes, in [0, 0xFFFF]
     */
    public static int update(int crc, byte[] data, int offset, int length) {
        int register = crc;
        for (int i = offset; i < offset + length; i++) {
            register = ((register << 8) ^ TABLE[((register >>> 8) ^ data[i]) & 0xFF]) & 0xFFFF;
        }
        return register;
    }
}
