package io.etherware.examples.scenario;

import static org.junit.jupiter.api.Assertions.assertEquals;
import static org.junit.jupiter.api.Assertions.assertFalse;
import static org.junit.jupiter.api.Assertions.assertTrue;

import io.etherware.pendulum.components.ControlCycle;
import java.util.ArrayList;
import java.util.List;
import org.junit.jupiter.api.Test;

class RunSummaryTest {

    private static final long P = Runs.PERIOD_NS;

    @Test
    void shouldCountEveryReleaseWithoutATimelyCommandAsADeadlineMiss() {
        List<ControlCycle> cycles = new ArrayList<>();
        for (long k = 0; k < 10; k++) {
            if (k == 3) {
                cycles.add(Runs.missed(k));                   // reading failed
            } else if (k == 5) {
                cycles.add(Runs.commanded(k, 1_000L, P + 1)); // commanded after its deadline
            } else if (k != 7) {                              // 7 never ran
                cycles.add(Runs.commanded(k, 1_000L, 3_000_000L));
            }
        }
        // Releases at P .. 10P; with the end at 11P the deadlines of the 10 releases have passed.
        RunSummary summary = RunSummary.of(Runs.run("a", Runs.samples(0.0, 0.01), cycles, List.of(), 11 * P));

        assertEquals(10, summary.releases());
        assertEquals(3, summary.deadlineMisses());
    }

    @Test
    void shouldNotCountAReleaseWhoseDeadlineIsStillAhead() {
        List<ControlCycle> cycles = List.of(Runs.commanded(0, 0, 1_000_000L));
        // First release at P, the end half a period after it: its deadline has not passed.
        RunSummary summary = RunSummary.of(Runs.run("a", Runs.samples(0.0), cycles, List.of(), P + P / 2));

        assertEquals(0, summary.releases());
        assertEquals(0, summary.deadlineMisses());
    }

    @Test
    void shouldMeasureJitterBetweenSuccessiveCommandsIncludingGaps() {
        // Commands 2 ms after each release for k = 0..3, then nothing until k = 70: a gap of 67 periods.
        List<ControlCycle> cycles = new ArrayList<>();
        for (long k = 0; k < 4; k++) {
            cycles.add(Runs.commanded(k, 0, 2_000_000L));
        }
        cycles.add(Runs.missed(4));
        cycles.add(Runs.commanded(70, 0, 2_000_000L));

        RunSummary summary = RunSummary.of(Runs.run("a", Runs.samples(0.0), cycles, List.of(), 80 * P));

        assertEquals(0.0, summary.jitterP50Ms(), 1e-9);
        assertEquals(66 * P / 1e6, summary.jitterMaxMs(), 1e-9);
        assertEquals(66 * P / 1e6, summary.jitterP99Ms(), 1e-9);
    }

    @Test
    void shouldReportTheFallAndWhenItHappened() {
        ProbeSamples samples = Runs.samples(0.02, -0.1, 0.3, -0.51, 1.2);
        RunSummary summary = RunSummary.of(Runs.run("a", samples, List.of(), List.of(), 10 * P));

        assertTrue(summary.fell());
        assertEquals(3 * P / 1e9, summary.fellAtS(), 1e-12);
        assertEquals(1.2, summary.maxAbsTheta2Rad(), 1e-12);
        double rms = Math.sqrt((0.02 * 0.02 + 0.01 + 0.09 + 0.51 * 0.51 + 1.44) / 5);
        assertEquals(rms, summary.rmsTheta2Rad(), 1e-12);
    }

    @Test
    void shouldNotReportAFallWithinTheThreshold() {
        RunSummary summary = RunSummary.of(Runs.run("a", Runs.samples(0.5, -0.49), List.of(), List.of(), 10 * P));

        assertFalse(summary.fell());
        assertTrue(Double.isNaN(summary.fellAtS()));
        assertTrue(Double.isNaN(summary.jitterMaxMs()), "no commands, no jitter");
    }
}
