package io.etherware.examples.upgrade;

import static org.junit.jupiter.api.Assertions.assertEquals;
import static org.junit.jupiter.api.Assertions.assertTrue;

import io.etherware.examples.scenario.Runs;
import io.etherware.examples.scenario.ScenarioRun;
import io.etherware.pendulum.components.ControlCycle;
import java.util.List;
import org.junit.jupiter.api.Test;

class UpgradeReportTest {

    private static final long P = Runs.PERIOD_NS;

    private static ControlCycle cycle(long k, int gainVersion) {
        ControlCycle base = Runs.commanded(k, 100_000L, 3_000_000L);
        return new ControlCycle(base.cycle(), base.releaseNs(), base.startNs(), base.readoutNs(), base.outcome(),
                0.0, 0.0, 0.0, 0.0, 0L, 0.0, gainVersion);
    }

    @Test
    void shouldMeasureTheHandOverFromV1sLastCommandToV2sFirst() {
        ScenarioRun run = Runs.run("upgrade", Runs.samples(0.0),
                List.of(cycle(0, 1), cycle(1, 1), Runs.missed(2), cycle(3, 2), cycle(4, 2)), List.of(), 6 * P);

        UpgradeReport.HandOver handOver = UpgradeReport.handOver(run).orElseThrow();

        assertEquals(1, handOver.lastV1().cycle());
        assertEquals(3, handOver.firstV2().cycle());
        assertEquals(2 * P, handOver.handOverNs());
        assertEquals(1, handOver.lostCycles());
    }

    @Test
    void shouldAccountForEveryCycleTheHandOverLost() {
        ScenarioRun run = Runs.run("upgrade", Runs.samples(0.0),
                List.of(cycle(0, 1), cycle(1, 1), Runs.missed(2), cycle(4, 2)), List.of(), 6 * P);

        List<String> lines = UpgradeReport.betweenLines(run, UpgradeReport.handOver(run).orElseThrow());

        assertEquals(2, lines.size(), () -> String.join("\n", lines));
        assertTrue(lines.get(0).startsWith("    cycle 2: MISSED by V"), lines.get(0));
        assertTrue(lines.get(1).startsWith("    cycle 3: no record"), lines.get(1));
    }

    @Test
    void shouldHaveNoHandOverWhenV2NeverCommanded() {
        ScenarioRun run = Runs.run("upgrade", Runs.samples(0.0), List.of(cycle(0, 1)), List.of(), 2 * P);
        assertTrue(UpgradeReport.handOver(run).isEmpty());
    }
}
