package io.etherware.examples.output;

import io.etherware.examples.scenario.ProbeSamples;
import io.etherware.examples.scenario.ScenarioEvent;
import io.etherware.examples.scenario.ScenarioRun;
import io.etherware.pendulum.components.ControlCycle;
import java.io.BufferedWriter;
import java.io.IOException;
import java.io.Writer;
import java.nio.charset.StandardCharsets;
import java.nio.file.Files;
import java.nio.file.Path;
import java.util.Comparator;
import java.util.List;
import java.util.Locale;

/**
 * Writes a run as CSV, one row per plant sample (one per control period):
 *
 * <pre>
 * time_s,theta1_rad,theta2_rad,u_nm,tick_lateness_ms,events
 * 2.0100,0.001534,-0.000767,0.0123,0.041,stress 1 start
 * </pre>
 *
 * {@code time_s} counts from the board's start; θ1, θ2 and {@code u_nm} (the torque the motor
 * applied, 0 once the board's watchdog cut it) are the plant's ground truth;
 * {@code tick_lateness_ms} is the largest start lateness of the controller's cycles released since
 * the previous row (empty when none ran: a Tick skipped, or a controller starved); {@code events}
 * lists the events since the previous row, separated by {@code ;}.
 *
 * <p>Stateless and thread-safe.
 */
public final class TraceCsv {

    /** The header row. */
    public static final String HEADER = "time_s,theta1_rad,theta2_rad,u_nm,tick_lateness_ms,events";

    private TraceCsv() {
    }

    /** Writes {@code run} to {@code file}, replacing it. */
    public static void write(ScenarioRun run, Path file) throws IOException {
        try (BufferedWriter out = Files.newBufferedWriter(file, StandardCharsets.UTF_8)) {
            write(run, out);
        }
    }

    /** Writes {@code run} to {@code out}, header first. */
    public static void write(ScenarioRun run, Writer out) throws IOException {
        ProbeSamples samples = run.samples();
        List<ControlCycle> cycles = run.cycles().stream().sorted(Comparator.comparingLong(ControlCycle::releaseNs))
                .toList();
        List<ScenarioEvent> events = run.events();
        out.write(HEADER);
        out.write('\n');
        int cycle = 0;
        int event = 0;
        var row = new StringBuilder(96);
        for (int i = 0; i < samples.size(); i++) {
            long timeNs = samples.timeNs()[i];
            long latenessNs = -1;
            while (cycle < cycles.size() && cycles.get(cycle).releaseNs() <= timeNs) {
                latenessNs = Math.max(latenessNs, cycles.get(cycle++).startLatenessNs());
            }
            row.setLength(0);
            row.append(String.format(Locale.ROOT, "%.4f,%.6f,%.6f,%.4f,", run.secondsOf(timeNs),
                    samples.theta1Rad()[i], samples.theta2Rad()[i], samples.torqueNm()[i]));
            if (latenessNs >= 0) {
                row.append(String.format(Locale.ROOT, "%.3f", latenessNs / 1e6));
            }
            row.append(',');
            boolean first = true;
            while (event < events.size() && events.get(event).timeNs() <= timeNs) {
                row.append(first ? "" : ";").append(events.get(event++).label());
                first = false;
            }
            out.append(row).append('\n');
        }
        // Events after the last sample (a stress ending as the run stops) still belong in the file,
        // each on a row of its own without samples.
        for (; event < events.size(); event++) {
            ScenarioEvent late = events.get(event);
            out.append(String.format(Locale.ROOT, "%.4f,,,,,%s\n", run.secondsOf(late.timeNs()), late.label()));
        }
    }
}
