package io.etherware.pendulum.serial;

import static org.junit.jupiter.api.Assertions.assertArrayEquals;
import static org.junit.jupiter.api.Assertions.assertEquals;
import static org.junit.jupiter.api.Assertions.assertFalse;
import static org.junit.jupiter.api.Assertions.assertThrows;
import static org.junit.jupiter.api.Assertions.assertTrue;

import io.etherware.pendulum.sim.LockStepClock;
import java.io.ByteArrayOutputStream;
import java.io.IOException;
import java.util.Arrays;
import org.junit.jupiter.api.Test;

class SimulatedSerialLinkTest {

    @Test
    void shouldDeliverBytesAtTheBaudRateInLockStep() throws IOException {
        LockStepClock clock = new LockStepClock();
        SimulatedSerialLink link = SimulatedSerialLink.lockStep(SimulatedSerialLink.Config.defaults(), clock);
        byte[] data = {1, 2, 3, 4, 5, 6, 7, 8, 9, 10};
        link.hostEnd().write(data, 0, data.length);
        byte[] buffer = new byte[64];

        assertEquals(0, link.boardEnd().read(buffer, 0, buffer.length, 0));
        clock.advanceTo(500_000L); // 5 bytes of 86.8 µs have arrived by then, not 6
        assertEquals(5, link.boardEnd().read(buffer, 0, buffer.length, 0));

        int n = link.boardEnd().read(buffer, 5, buffer.length - 5, 10_000_000L);
        assertEquals(1, n, "a waiting read returns as soon as the next byte arrives");
        assertEquals(Math.round(6 * 1e9 * 10 / 115_200), clock.nanoTime());
        clock.advanceTo(1_000_000L);
        assertEquals(4, link.boardEnd().read(buffer, 6, buffer.length - 6, 0));
        assertArrayEquals(data, Arrays.copyOf(buffer, 10));
    }

    @Test
    void shouldQueueBackToBackWritesOnTheWire() throws IOException {
        LockStepClock clock = new LockStepClock();
        SimulatedSerialLink link = SimulatedSerialLink.lockStep(
                SimulatedSerialLink.Config.defaults().withBaudRate(1_000_000), clock);
        link.hostEnd().write(new byte[100], 0, 100); // 1 ms on the wire at 10 bits per byte
        link.hostEnd().write(new byte[1], 0, 1);
        byte[] buffer = new byte[200];
        clock.advanceTo(1_000_000L);
        assertEquals(100, link.boardEnd().read(buffer, 0, buffer.length, 0));
        clock.advanceTo(1_009_999L);
        assertEquals(0, link.boardEnd().read(buffer, 0, buffer.length, 0));
        clock.advanceTo(1_010_000L);
        assertEquals(1, link.boardEnd().read(buffer, 0, buffer.length, 0));
    }

    @Test
    void shouldTimeOutInSimulatedTimeWhenNothingIsSent() throws IOException {
        LockStepClock clock = new LockStepClock();
        SimulatedSerialLink link = SimulatedSerialLink.lockStep(SimulatedSerialLink.Config.defaults(), clock);
        assertEquals(0, link.hostEnd().read(new byte[8], 0, 8, 3_000_000L));
        assertEquals(3_000_000L, clock.nanoTime());
    }

    @Test
    void shouldInjectFaultsAtTheConfiguredRatesAndReproduceThemFromTheSeed() throws IOException {
        byte[] first = pushThrough(0.01, 0.005, 42L);
        byte[] again = pushThrough(0.01, 0.005, 42L);
        byte[] other = pushThrough(0.01, 0.005, 43L);
        assertArrayEquals(first, again);
        assertFalse(Arrays.equals(first, other));
    }

    @Test
    void shouldCountFlippedAndDroppedBytesNearTheirProbabilities() throws IOException {
        LockStepClock clock = new LockStepClock();
        SimulatedSerialLink link = SimulatedSerialLink.lockStep(SimulatedSerialLink.Config.defaults()
                .withBaudRate(10_000_000).withFaults(0.01, 0.005, 5L), clock);
        byte[] zeros = new byte[1000];
        byte[] buffer = new byte[4096];
        long received = 0;
        long nonZero = 0;
        for (int i = 0; i < 100; i++) {
            link.hostEnd().write(zeros, 0, zeros.length);
            clock.advanceTo(clock.nanoTime() + 2_000_000L);
            int n = link.boardEnd().read(buffer, 0, buffer.length, 0);
            received += n;
            for (int j = 0; j < n; j++) {
                nonZero += buffer[j] != 0 ? 1 : 0;
            }
        }
        SimulatedSerialLink.Counters counters = link.hostToBoardCounters();
        assertEquals(100_000, counters.bytesSent());
        assertTrue(counters.bytesFlipped() > 850 && counters.bytesFlipped() < 1150, counters::toString);
        assertTrue(counters.bytesDropped() > 400 && counters.bytesDropped() < 600, counters::toString);
        assertEquals(counters.bytesSent() - counters.bytesDropped(), received);
        assertEquals(counters.bytesFlipped(), nonZero, "exactly one bit flipped in each flipped byte");
    }

    @Test
    void shouldTakeTheWireTimeInRealTime() throws IOException {
        SimulatedSerialLink link = SimulatedSerialLink.realTime(SimulatedSerialLink.Config.defaults());
        byte[] data = new byte[100];
        Arrays.fill(data, (byte) 0x5A);
        long start = System.nanoTime();
        link.boardEnd().write(data, 0, data.length);
        ByteArrayOutputStream received = new ByteArrayOutputStream();
        byte[] buffer = new byte[32];
        while (received.size() < data.length && System.nanoTime() - start < 5_000_000_000L) {
            int n = link.hostEnd().read(buffer, 0, buffer.length, 100_000_000L);
            received.write(buffer, 0, n);
        }
        long elapsedNs = System.nanoTime() - start;
        assertArrayEquals(data, received.toByteArray());
        // 100 bytes x 86.8 µs: they cannot all be there before 8.68 ms.
        assertTrue(elapsedNs >= 8_600_000L, () -> "elapsed " + elapsedNs + " ns");
    }

    @Test
    void shouldFailClearlyWhenAnEndIsClosed() {
        SimulatedSerialLink link = SimulatedSerialLink.realTime(SimulatedSerialLink.Config.defaults());
        link.hostEnd().close();
        IOException error = assertThrows(IOException.class, () -> link.hostEnd().read(new byte[4], 0, 4, 0));
        assertTrue(error.getMessage().contains("simulated-host is closed"), error.getMessage());
    }

    @Test
    void shouldNameTheFieldOfAnInvalidConfig() {
        var error = assertThrows(IllegalArgumentException.class,
                () -> SimulatedSerialLink.Config.defaults().withFaults(1.5, 0, 1));
        assertTrue(error.getMessage().startsWith("bitFlipProbabilityPerByte=1.5"), error.getMessage());
    }

    private static byte[] pushThrough(double flip, double drop, long seed) throws IOException {
        LockStepClock clock = new LockStepClock();
        SimulatedSerialLink link = SimulatedSerialLink.lockStep(SimulatedSerialLink.Config.defaults()
                .withFaults(flip, drop, seed), clock);
        byte[] data = new byte[2000];
        for (int i = 0; i < data.length; i++) {
            data[i] = (byte) i;
        }
        link.hostEnd().write(data, 0, 1000);
        link.hostEnd().write(data, 1000, 1000);
        clock.advanceTo(1_000_000_000L);
        byte[] buffer = new byte[4096];
        int n = link.boardEnd().read(buffer, 0, buffer.length, 0);
        return Arrays.copyOf(buffer, n);
    }
}
