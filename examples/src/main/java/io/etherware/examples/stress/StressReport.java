package io.etherware.examples.stress;

import io.etherware.examples.output.ComparisonTable;
import io.etherware.examples.output.TraceCsv;
import io.etherware.examples.output.TracePlots;
import io.etherware.examples.scenario.RunSummary;
import io.etherware.examples.scenario.ScenarioRun;
import java.awt.AWTError;
import java.io.IOException;
import java.nio.charset.StandardCharsets;
import java.nio.file.Files;
import java.nio.file.Path;
import java.util.ArrayList;
import java.util.List;
import java.util.Locale;
import org.slf4j.Logger;
import org.slf4j.LoggerFactory;

/**
 * Writes the stress scenario's results into its output directory: per run a CSV
 * ({@code stress-<run>.csv}) and a plot ({@code stress-<run>.png/.svg}); the runs overlaid in
 * one plot ({@code stress.png/.svg}); and the table with the run notes
 * ({@code summary.txt}). The CSVs and the table are written first, so a plotting failure (no
 * fonts on a headless box, say) loses nothing else: it is logged and the plot is left out.
 *
 * <p>Stateless and thread-safe.
 */
public final class StressReport {

    private static final Logger LOG = LoggerFactory.getLogger(StressReport.class);

    private StressReport() {
    }

    /** The heading line of the table: what ran. */
    public static String heading(StressConfig config) {
        return String.format(Locale.ROOT, "stress (paper Section VI-B): %.0f s per run; controller on HIGH Ticks every %d ms;"
                + " stress task on LOW Ticks every %.1f s computing %d ms; %d load threads allocating",
                config.durationNs() / 1e9, config.periodNs() / 1_000_000, config.stressEveryNs() / 1e9,
                config.stressWorkNs() / 1_000_000, config.loadThreads()) + setup(config);
    }

    /** The serial line rate and the CPU partition, as they appear in a heading. */
    public static String setup(StressConfig config) {
        return "; serial link " + config.baudRate() + " baud" + (config.realtimeCpus().isInherit() ? ""
                : "; CPUs partitioned, real-time threads on " + config.realtimeCpus());
    }

    /** Writes everything; returns the files written, in order. */
    public static List<Path> write(StressConfig config, List<ScenarioRun> runs, List<RunSummary> summaries)
            throws IOException {
        return write(config.out(), "stress", "Stress", heading(config), ComparisonTable.format(runs, summaries), runs);
    }

    /**
     * Writes a stress-like scenario's files into {@code out}: {@code <name>-<run>.csv} and
     * {@code .png/.svg} per run, {@code <name>.png/.svg} with the runs overlaid, and {@code summary.txt} with
     * {@code heading}, {@code table} and the run notes; {@code what} begins the plot titles.
     * Returns the files written, in order.
     */
    public static List<Path> write(Path out, String name, String what, String heading, String table,
            List<ScenarioRun> runs) throws IOException {
        Files.createDirectories(out);
        List<Path> written = new ArrayList<>();
        for (ScenarioRun run : runs) {
            Path csv = out.resolve(name + "-" + run.key() + ".csv");
            TraceCsv.write(run, csv);
            written.add(csv);
        }
        Path summary = out.resolve("summary.txt");
        var text = new StringBuilder(heading).append("\n\n").append(table).append('\n');
        runs.forEach(run -> run.notes().forEach(note -> text.append(note).append('\n')));
        Files.writeString(summary, text, StandardCharsets.UTF_8);
        written.add(summary);

        for (ScenarioRun run : runs) {
            plot(written, () -> TracePlots.of(run, what + ", " + run.title())
                    .save(out.resolve(name + "-" + run.key())));
        }
        String titles = String.join(" vs ", runs.stream().map(ScenarioRun::title).toList());
        plot(written, () -> TracePlots.of(runs, what + ": " + titles).save(out.resolve(name)));
        return written;
    }

    private interface PlotJob {
        List<Path> run() throws IOException;
    }

    private static void plot(List<Path> written, PlotJob job) {
        try {
            written.addAll(job.run());
        } catch (IOException | RuntimeException | LinkageError | AWTError e) {
            // LinkageError and AWTError: a JDK without its font or imaging libraries.
            LOG.error("could not draw a plot ({}); the CSV and summary are complete", e.toString(), e);
        }
    }
}
