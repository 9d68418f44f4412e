package io.etherware.pendulum.serial;

import static org.junit.jupiter.api.Assertions.assertEquals;
import static org.junit.jupiter.api.Assertions.assertNotEquals;

import java.nio.charset.StandardCharsets;
import org.junit.jupiter.api.Test;

class Crc16Test {

    @Test
    void shouldMatchTheCcittFalseCheckValue() {
        byte[] check = "123456789".getBytes(StandardCharsets.US_ASCII);
        assertEquals(0x29B1, Crc16.of(check, 0, check.length));
    }

    @Test
    void shouldGiveTheInitialValueForNoBytesAndChainAcrossCalls() {
        byte[] check = "123456789".getBytes(StandardCharsets.US_ASCII);
        assertEquals(0xFFFF, Crc16.of(check, 0, 0));
        int chained = Crc16.update(Crc16.of(check, 0, 4), check, 4, 5);
        assertEquals(0x29B1, chained);
    }

    @Test
    void shouldChangeWhenAnySingleBitFlips() {
        byte[] frame = new byte[DspProtocol.MAX_FRAME_BYTES];
        int length = DspProtocol.encodeAngles(frame, 7, 1234, -56, 999_999L);
        int crc = Crc16.of(frame, 1, length - 3);
        for (int bit = 8; bit < (length - 2) * 8; bit++) {
            frame[bit / 8] ^= (byte) (1 << (bit % 8));
            assertNotEquals(crc, Crc16.of(frame, 1, length - 3), "bit " + bit);
            frame[bit / 8] ^= (byte) (1 << (bit % 8));
        }
    }
}
