package io.etherware.examples.output;

import static org.junit.jupiter.api.Assertions.assertEquals;
import static org.junit.jupiter.api.Assertions.assertThrows;
import static org.junit.jupiter.api.Assertions.assertTrue;

import io.etherware.examples.scenario.RunSummary;
import io.etherware.examples.scenario.Runs;
import io.etherware.examples.scenario.ScenarioRun;
import java.util.List;
import org.junit.jupiter.api.Test;

class ComparisonTableTest {

    @Test
    void shouldPutTheRunsSideBySideWithOneRowPerFigure() {
        ScenarioRun fifo = Runs.run("fifo", Runs.samples(0.0), List.of(), List.of(), Runs.PERIOD_NS);
        ScenarioRun rt = Runs.run("rt", Runs.samples(0.0), List.of(), List.of(), Runs.PERIOD_NS);
        var fell = new RunSummary(3.14159, 0.8, 1.5, 0.5, 48.25, 1_200.0, 400, 665, true, 2.5);
        var held = new RunSummary(0.0204, 0.05, 0.0029, 0.006, 7.6, 89.4, 18, 665, false, Double.NaN);

        List<String> lines = ComparisonTable.lines(List.of(fifo, rt), List.of(fell, held));

        assertEquals(9, lines.size());
        assertTrue(lines.get(0).trim().matches("run fifo\\s+run rt"), lines.get(0));
        assertTrue(lines.get(1).matches("max \\|θ2\\| \\(rad\\)\\s+3\\.1416\\s+0\\.0204"), lines.get(1));
        assertTrue(lines.get(7).matches("deadline misses\\s+400 of 665\\s+18 of 665"), lines.get(7));
        assertTrue(lines.get(8).matches("fell \\(\\|θ2\\| > 0\\.5 rad\\)\\s+yes, at 2\\.50 s\\s+no"), lines.get(8));
        int column = lines.get(0).length();
        lines.forEach(line -> assertEquals(column, line.length(), () -> "columns line up: '" + line + "'"));
    }

    @Test
    void shouldRefuseRunsAndSummariesThatDoNotPair() {
        ScenarioRun run = Runs.run("fifo", Runs.samples(0.0), List.of(), List.of(), Runs.PERIOD_NS);
        assertThrows(IllegalArgumentException.class, () -> ComparisonTable.format(List.of(run), List.of()));
    }
}
