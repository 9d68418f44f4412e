package io.etherware.examples.output;

import io.etherware.examples.scenario.RunSummary;
import io.etherware.examples.scenario.ScenarioRun;
import java.awt.AWTError;
import java.io.IOException;
import java.io.PrintWriter;
import java.nio.charset.StandardCharsets;
import java.nio.file.Files;
import java.nio.file.Path;
import java.util.ArrayList;
import java.util.List;
import org.slf4j.Logger;
import org.slf4j.LoggerFactory;

/**
 * The report of a scenario that changes something mid-run (an upgrade, a migration): one run, two
 * phases compared side by side (before and after the change), the lines about the change itself,
 * and the run's notes; written as {@code <name>.csv}, {@code summary.txt} and
 * {@code <name>.png/.svg}, and printed the same way.
 *
 * <p>Immutable; stateless methods, thread-safe.
 *
 * @param heading     the line that says what ran
 * @param run         the whole run
 * @param phases      before and after, slices of {@code run}
 * @param changeLines what the change did and cost
 */
public record PhaseReport(String heading, ScenarioRun run, List<ScenarioRun> phases, List<String> changeLines) {

    private static final Logger LOG = LoggerFactory.getLogger(PhaseReport.class);

    public PhaseReport {
        phases = List.copyOf(phases);
        changeLines = List.copyOf(changeLines);
    }

    /** The phases' table, the change's lines and the run's notes, as {@code summary.txt} holds them after the heading. */
    public String body() {
        var text = new StringBuilder(ComparisonTable.format(phases, phases.stream().map(RunSummary::of).toList()))
                .append('\n');
        changeLines.forEach(line -> text.append(line).append('\n'));
        text.append('\n');
        run.notes().forEach(note -> text.append(note).append('\n'));
        return text.toString();
    }

    /**
     * Writes {@code <name>.csv}, {@code summary.txt} and the run's plot ({@link TracePlots})
     * titled {@code plotTitle} into {@code out}; returns the files written. A plot that cannot be
     * drawn is logged; the CSV and the summary are written anyway.
     */
    public List<Path> write(Path out, String name, String plotTitle) throws IOException {
        Files.createDirectories(out);
        List<Path> written = new ArrayList<>();
        Path csv = out.resolve(name + ".csv");
        TraceCsv.write(run, csv);
        written.add(csv);
        Path summary = out.resolve("summary.txt");
        Files.writeString(summary, heading + "\n\n" + body(), StandardCharsets.UTF_8);
        written.add(summary);
        try {
            written.addAll(TracePlots.of(run, plotTitle).save(out.resolve(name)));
        } catch (IOException | RuntimeException | LinkageError | AWTError e) {
            LOG.error("could not draw the plot ({}); the CSV and summary are complete", e.toString(), e);
        }
        return written;
    }

    /** Prints the body and the files {@code written} to {@code out} (the heading went out before the run). */
    public void print(PrintWriter out, List<Path> written) {
        out.println();
        out.print(body());
        out.println();
        out.println("Wrote:");
        written.forEach(path -> out.println("  " + path.toAbsolutePath().normalize()));
        out.flush();
    }
}
