package io.etherware.examples.output;

import static org.junit.jupiter.api.Assertions.assertEquals;

import io.etherware.examples.scenario.Runs;
import io.etherware.examples.scenario.ScenarioEvent;
import java.io.StringWriter;
import java.util.List;
import org.junit.jupiter.api.Test;

class TraceCsvTest {

    private static final long P = Runs.PERIOD_NS;

    @Test
    void shouldWriteOneRowPerSampleWithTheLatenessOfTheCyclesReleasedSinceThePreviousRow() throws Exception {
        var run = Runs.run("fifo", Runs.samples(0.02, 0.01, -0.005, 0.0),
                List.of(Runs.commanded(0, 250_000L, 3_000_000L), Runs.commanded(1, 1_500_000L, 4_000_000L)),
                List.of(new ScenarioEvent(2 * P - 1, ScenarioEvent.Kind.STRESS_START, "stress 1 start"),
                        new ScenarioEvent(2 * P, ScenarioEvent.Kind.NOTE, "note"),
                        new ScenarioEvent(9 * P, ScenarioEvent.Kind.STRESS_END, "stress 1 end")),
                4 * P);
        var out = new StringWriter();

        TraceCsv.write(run, out);

        assertEquals(List.of(
                TraceCsv.HEADER,
                "0.0000,0.010000,0.020000,0.0100,,",
                "0.0150,0.005000,0.010000,0.0100,0.250,",
                "0.0300,-0.002500,-0.005000,0.0100,1.500,stress 1 start;note",
                "0.0450,0.000000,0.000000,0.0100,,",
                "0.1350,,,,,stress 1 end"), out.toString().lines().toList());
    }
}
