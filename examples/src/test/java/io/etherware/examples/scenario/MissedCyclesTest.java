package io.etherware.examples.scenario;

import static org.junit.jupiter.api.Assertions.assertEquals;
import static org.junit.jupiter.api.Assertions.assertTrue;

import io.etherware.pendulum.components.ControlCycle;
import java.util.ArrayList;
import java.util.List;
import java.util.Optional;
import org.junit.jupiter.api.Test;

class MissedCyclesTest {

    private static final long P = Runs.PERIOD_NS;

    @Test
    void shouldListEachMissAtItsReleaseWithWhatBecameOfIt() {
        List<ControlCycle> cycles = new ArrayList<>();
        for (long k = 0; k < 10; k++) {
            if (k == 3) {
                cycles.add(Runs.missed(k));                           // reading failed
            } else if (k == 5) {
                cycles.add(Runs.commanded(k, 2_000_000L, P + 500_000L)); // commanded after its deadline
            } else if (k != 7) {                                      // 7 never ran
                cycles.add(Runs.commanded(k, 1_000L, 3_000_000L));
            }
        }
        // Releases at P .. 10P (k = 0 .. 9), the end at 11P; time 0 of the note is the origin, 0.
        Optional<String> note = MissedCycles.note(cycles, P, 0L, P, 11 * P);

        assertEquals(Optional.of("  deadline misses at (s since the board started): 0.06 (no reading, given up 10.0 ms"
                + " after its release, started 0.0 ms late), 0.09 (torque 15.5 ms after its release, started 2.0 ms"
                + " late); 1 release without a control cycle, at 0.12"), note);
        ScenarioRun run = Runs.run("a", Runs.samples(0.0), cycles, List.of(), 11 * P);
        assertEquals(3, RunSummary.of(run).deadlineMisses(), "the same misses as the summary counts");
    }

    @Test
    void shouldSayNothingForARunWithoutMissesNorCountAReleaseWhoseDeadlineIsAhead() {
        List<ControlCycle> cycles = List.of(Runs.commanded(0, 0, 1_000_000L), Runs.commanded(1, 0, 1_000_000L),
                Runs.missed(2));
        // The end half a period after the third release: its deadline has not passed, so it is no miss yet.
        assertEquals(Optional.empty(), MissedCycles.note(cycles, P, 0L, P, 3 * P + P / 2));
    }

    @Test
    void shouldCountAReleaseAsOnTimeWhenAnyOfItsCyclesWas() {
        // A cycle recorded twice (a replay): once late, once on time.
        List<ControlCycle> cycles = List.of(Runs.commanded(0, 0, P + 1), Runs.commanded(0, 0, 1_000_000L));
        assertEquals(Optional.empty(), MissedCycles.note(cycles, P, 0L, P, 2 * P));
    }

    @Test
    void shouldListTheFirstMissesAndCountTheRest() {
        List<ControlCycle> cycles = new ArrayList<>();
        for (long k = 0; k < 20; k++) {
            cycles.add(Runs.missed(k));
        }
        String note = MissedCycles.note(cycles, P, 0L, P, 21 * P).orElseThrow();

        assertEquals(MissedCycles.LISTED, note.split("no reading").length - 1, note);
        assertTrue(note.endsWith(", and " + (20 - MissedCycles.LISTED) + " more"), note);
    }
}
