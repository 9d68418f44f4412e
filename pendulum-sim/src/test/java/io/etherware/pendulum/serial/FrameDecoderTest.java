package io.etherware.pendulum.serial;

import static org.junit.jupiter.api.Assertions.assertArrayEquals;
import static org.junit.jupiter.api.Assertions.assertEquals;
import static org.junit.jupiter.api.Assertions.assertTrue;

import java.io.ByteArrayOutputStream;
import java.util.ArrayList;
import java.util.Arrays;
import java.util.List;
import java.util.Random;
import org.junit.jupiter.api.Test;

class FrameDecoderTest {

    record Decoded(int type, byte[] payload) {}

    private final FrameDecoder decoder = new FrameDecoder();
    private final List<Decoded> frames = new ArrayList<>();

    private void feed(byte[] bytes) {
        decoder.accept(bytes, 0, bytes.length, (type, payload, offset, length) ->
                frames.add(new Decoded(type, Arrays.copyOfRange(payload, offset, offset + length))));
    }

    private static byte[] anglesFrame(int sequence) {
        byte[] frame = new byte[DspProtocol.MAX_FRAME_BYTES];
        int length = DspProtocol.encodeAngles(frame, sequence, 100 + sequence, -sequence, 1000L * sequence);
        return Arrays.copyOf(frame, length);
    }

    private static byte[] torqueFrame(int sequence, double torqueNm) {
        byte[] frame = new byte[DspProtocol.MAX_FRAME_BYTES];
        return Arrays.copyOf(frame, DspProtocol.encodeSetTorque(frame, sequence, torqueNm));
    }

    @Test
    void shouldDecodeBackToBackFramesFedOneByteAtATime() {
        byte[] stream = concat(anglesFrame(1), torqueFrame(2, -0.125), anglesFrame(3));
        for (byte b : stream) {
            feed(new byte[] {b});
        }
        assertEquals(3, frames.size());
        assertEquals(DspProtocol.SET_TORQUE, frames.get(1).type());
        assertEquals(-125_000, DspProtocol.getI32(frames.get(1).payload(), 2));
        assertEquals(3, decoder.framesAccepted());
        assertEquals(0, decoder.framesRejected());
    }

    @Test
    void shouldResynchronizeAfterGarbageThatContainsStartBytes() {
        byte[] garbage = {0x13, (byte) 0xA5, (byte) 0xA5, 0x01, 0x02, (byte) 0xA5, (byte) 0x81, 0x0E, 0x55};
        feed(concat(garbage, anglesFrame(9)));
        feed(concat(new byte[] {(byte) 0xA5}, anglesFrame(10)));

        assertEquals(2, frames.size(), () -> "frames " + frames.size());
        assertEquals(9, DspProtocol.getU16(frames.get(0).payload(), 0));
        assertEquals(10, DspProtocol.getU16(frames.get(1).payload(), 0));
        assertTrue(decoder.framesRejected() >= 3, () -> "rejected " + decoder.framesRejected());
    }

    @Test
    void shouldRejectACorruptFrameAndStillDecodeTheNextOne() {
        byte[] corrupt = anglesFrame(1);
        corrupt[6] ^= 0x10;
        feed(concat(corrupt, anglesFrame(2)));

        assertEquals(1, frames.size());
        assertEquals(2, DspProtocol.getU16(frames.getFirst().payload(), 0));
        assertEquals(1, decoder.framesRejected());
    }

    @Test
    void shouldRecoverTheNextFrameWhenAByteOfAFrameWasLost() {
        byte[] truncated = anglesFrame(1);
        byte[] shortened = concat(Arrays.copyOfRange(truncated, 0, 8),
                Arrays.copyOfRange(truncated, 9, truncated.length));
        feed(concat(shortened, anglesFrame(2), anglesFrame(3)));

        List<Integer> sequences = frames.stream().map(f -> DspProtocol.getU16(f.payload(), 0)).toList();
        assertEquals(List.of(2, 3), sequences);
    }

    @Test
    void shouldNeverThrowAndAlmostNeverAcceptRandomNoise() {
        // Noise laced with start bytes makes thousands of candidate frames; each passes the
        // type, length and CRC checks with probability about 6/256 * 1/256 * 2^-16.
        Random random = new Random(7);
        for (int round = 0; round < 200; round++) {
            byte[] noise = new byte[500];
            random.nextBytes(noise);
            for (int i = 0; i < noise.length; i += 17) {
                noise[i] = (byte) 0xA5;
            }
            feed(noise);
        }
        for (Decoded frame : frames) {
            assertEquals(DspProtocol.payloadBytes(frame.type()), frame.payload().length);
        }
        assertTrue(decoder.framesRejected() > 1000, () -> "rejected " + decoder.framesRejected());
        assertTrue(frames.size() < 3, () -> "accepted " + frames.size() + " frames of noise");
        assertTrue(decoder.bufferedBytes() < DspProtocol.MAX_FRAME_BYTES);
    }

    @Test
    void shouldDecodeEveryCleanFrameAfterANoisyPrefix() {
        Random random = new Random(11);
        ByteArrayOutputStream stream = new ByteArrayOutputStream();
        for (int i = 0; i < 50; i++) {
            byte[] noise = new byte[random.nextInt(40)];
            random.nextBytes(noise);
            stream.writeBytes(noise);
            stream.writeBytes(anglesFrame(1000 + i));
        }
        feed(stream.toByteArray());
        long clean = frames.stream().filter(f -> f.type() == DspProtocol.ANGLES
                && DspProtocol.getU16(f.payload(), 0) >= 1000).count();
        assertEquals(50, clean);
    }

    @Test
    void shouldRoundTripTheStatusLayout() {
        BoardStatus status = new BoardStatus(DspProtocol.FAULT_WATCHDOG, 4_000_000_000L, 10, 2, 30, 1,
                7, -0.25, 4096);
        byte[] frame = new byte[DspProtocol.MAX_FRAME_BYTES];
        int length = status.encode(frame, 77);
        feed(Arrays.copyOf(frame, length));
        assertEquals(1, frames.size());
        assertEquals(77, DspProtocol.getU16(frames.getFirst().payload(), 0));
        assertEquals(status, BoardStatus.decode(frames.getFirst().payload(), 0));
        assertArrayEquals(frames.getFirst().payload(), Arrays.copyOfRange(frame, 3, length - 2));
    }

    private static byte[] concat(byte[]... parts) {
        ByteArrayOutputStream out = new ByteArrayOutputStream();
        for (byte[] part : parts) {
            out.writeBytes(part);
        }
        return out.toByteArray();
    }
}
