package io.etherware.deploy.view;

import static org.junit.jupiter.api.Assertions.assertArrayEquals;
import static org.junit.jupiter.api.Assertions.assertEquals;
import static org.junit.jupiter.api.Assertions.assertThrows;
import static org.junit.jupiter.api.Assertions.assertTrue;

import org.junit.jupiter.api.Test;

class LiveSignalsTest {

    @Test
    void shouldKeepTheNewestSamplesOldestFirstWhenTheRingWraps() {
        LiveSignals.Signal signal = new LiveSignals(3).create("theta1", "rad");
        for (int i = 1; i <= 5; i++) {
            signal.record(i * 10L, i * 0.5);
        }

        LiveSignals.Samples samples = signal.samples();

        assertEquals(5, signal.recorded());
        assertArrayEquals(new long[] {30, 40, 50}, samples.timesNs());
        assertArrayEquals(new double[] {1.5, 2.0, 2.5}, samples.values());
    }

    @Test
    void shouldGiveNoSamplesBeforeTheFirst() {
        assertEquals(0, new LiveSignals().create("u", "N·m").samples().size());
    }

    @Test
    void shouldRefuseATakenNameAndANameThatIsNoIdentifier() {
        var signals = new LiveSignals();
        signals.create("theta2", "rad");

        var taken = assertThrows(IllegalArgumentException.class, () -> signals.create("theta2", "deg"));
        var bad = assertThrows(IllegalArgumentException.class, () -> signals.create("θ 2", "rad"));

        assertTrue(taken.getMessage().contains("already published"), taken.getMessage());
        assertTrue(bad.getMessage().contains("name=\"θ 2\""), bad.getMessage());
        assertEquals(1, signals.signals().size());
    }

    @Test
    void shouldNeverHandAReaderASampleTheWriterIsOverwriting() throws Exception {
        // The writer records value == time; a torn or overwritten pair would break the equality.
        LiveSignals.Signal signal = new LiveSignals(16).create("x", "");
        var writer = Thread.ofPlatform().start(() -> {
            for (long i = 1; i <= 2_000_000; i++) {
                signal.record(i, i);
            }
        });
        long reads = 0;
        while (writer.isAlive() || reads == 0) {
            LiveSignals.Samples samples = signal.samples();
            for (int i = 0; i < samples.size(); i++) {
                assertEquals((double) samples.timesNs()[i], samples.values()[i]);
                if (i > 0) {
                    assertEquals(samples.timesNs()[i - 1] + 1, samples.timesNs()[i]);
                }
            }
            reads++;
        }
        writer.join();
        assertEquals(2_000_000, signal.recorded());
    }
}
