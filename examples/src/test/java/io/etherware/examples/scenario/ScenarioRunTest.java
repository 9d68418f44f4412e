package io.etherware.examples.scenario;

import static org.junit.jupiter.api.Assertions.assertEquals;
import static org.junit.jupiter.api.Assertions.assertThrows;

import java.util.List;
import org.junit.jupiter.api.Test;

class ScenarioRunTest {

    private static final long P = Runs.PERIOD_NS;

    @Test
    void shouldSliceSamplesCyclesAndEventsOnTheRunsReleaseGrid() {
        ScenarioRun run = Runs.run("all", Runs.samples(0.0, 0.1, 0.2, 0.3, 0.4, 0.5),
                List.of(Runs.commanded(0, 0, 1_000), Runs.commanded(1, 0, 1_000), Runs.commanded(2, 0, 1_000),
                        Runs.commanded(3, 0, 1_000)),
                List.of(new ScenarioEvent(P / 2, ScenarioEvent.Kind.NOTE, "early"),
                        new ScenarioEvent(3 * P, ScenarioEvent.Kind.UPGRADE, "upgrade request")), 6 * P);

        ScenarioRun after = run.slice("v2", "after", 2 * P + 1, 6 * P);

        assertEquals(3 * P, after.firstReleaseNs(), "the next release on the grid");
        assertEquals(List.of(3 * P, 4 * P, 5 * P), java.util.Arrays.stream(after.samples().timeNs()).boxed().toList());
        assertEquals(List.of(2L, 3L), after.cycles().stream().map(c -> c.cycle()).toList());
        assertEquals(List.of("upgrade request"), after.events().stream().map(ScenarioEvent::label).toList());
        assertEquals(0L, after.originNs(), "times keep the run's origin");
        assertEquals(6 * P, after.endNs());
        assertEquals(3, RunSummary.of(after).releases(), "releases 3P, 4P and 5P are due by 6P");
    }

    @Test
    void shouldRefuseASliceThatEndsBeforeItStarts() {
        ScenarioRun run = Runs.run("all", Runs.samples(0.0), List.of(), List.of(), 2 * P);
        assertThrows(IllegalArgumentException.class, () -> run.slice("x", "x", P, 0));
    }
}
