package io.etherware.examples.bench;

import com.fasterxml.jackson.databind.ObjectMapper;
import com.fasterxml.jackson.databind.SerializationFeature;
import java.io.IOException;
import java.nio.file.Files;
import java.nio.file.Path;
import java.util.List;
import java.util.Locale;

/**
 * A finished bench run: the machine, the settings and every row, rendered as a markdown table
 * ({@code report.md}) and as JSON of the raw percentiles in nanoseconds ({@code report.json}).
 * Immutable.
 *
 * @param startedAt   when the run started, ISO-8601 UTC
 * @param settings    the run's settings as one line, e.g. {@code --duration 60}
 * @param machine     the machine and JVM
 * @param rows        every row, in report order
 * @param gcPauses    the collector pauses seen during the run
 * @param elapsedS    the run's wall-clock length in seconds
 */
public record BenchReport(String startedAt, String settings, MachineInfo machine, List<BenchRow> rows,
                          CollectorPauses.Summary gcPauses, double elapsedS) {

    /** File name of the markdown report. */
    public static final String MARKDOWN_FILE = "report.md";
    /** File name of the JSON report. */
    public static final String JSON_FILE = "report.json";

    /** Copies the rows. */
    public BenchReport {
        rows = List.copyOf(rows);
    }

    /** Writes {@code report.md} and {@code report.json} into {@code directory} (created if needed). */
    public void write(Path directory) throws IOException {
        Files.createDirectories(directory);
        Files.writeString(directory.resolve(MARKDOWN_FILE), markdown());
        new ObjectMapper().enable(SerializationFeature.INDENT_OUTPUT).writeValue(directory.resolve(JSON_FILE).toFile(), this);
    }

    /** Reads a {@code report.json} back (the smoke test checks it). */
    public static BenchReport read(Path json) throws IOException {
        return new ObjectMapper().readValue(json.toFile(), BenchReport.class);
    }

    /** The report as markdown: a header with the machine, then one table of every row. */
    public String markdown() {
        var text = new StringBuilder();
        text.append("# Etherware-RT bench\n\n");
        text.append(String.format(Locale.ROOT, "Run %s, %s, %.0f s in all.%n%n", startedAt, settings, elapsedS));
        text.append("| machine | |\n|---|---|\n");
        text.append("| cores | ").append(machine.cores()).append(" |\n");
        text.append("| kernel | ").append(machine.kernel()).append(" |\n");
        text.append("| JDK | ").append(machine.jdk()).append(" |\n");
        text.append("| JVM options | `").append(String.join(" ", machine.jvmOptions())).append("` |\n");
        text.append("| collectors | ").append(String.join(", ", machine.collectors())).append(" |\n");
        text.append("| SCHED_FIFO | ").append(machine.schedFifoGranted() ? "granted" : "NOT granted")
                .append(" (read back: ").append(machine.sched()).append(')')
                .append(machine.schedNote().isEmpty() ? "" : "; " + machine.schedNote()).append(" |\n");
        text.append("| load average at start | ").append(machine.loadAverage()).append(" |\n\n");
        text.append("| # | variant | condition | n | p50 | p99 | p99.9 | max | unit | figure | aim | verdict | note |\n");
        text.append("|---|---|---|--:|--:|--:|--:|--:|---|--:|---|---|---|\n");
        for (BenchRow row : rows) {
            text.append(markdownRow(row)).append('\n');
        }
        text.append('\n').append(gcPauses.markdown());
        return text.toString();
    }

    private static String markdownRow(BenchRow row) {
        Percentiles p = row.percentiles();
        boolean hasPercentiles = row.measured() && p.count() > 0;
        String figure = Double.isNaN(row.value()) ? "" : formatValue(row.value()) + " " + row.valueUnit();
        return String.join(" | ", "| " + row.section(), row.variant(), row.condition(),
                hasPercentiles ? Long.toString(p.count()) : "",
                hasPercentiles ? format(row.inUnit(p.p50Ns())) : "",
                hasPercentiles ? format(row.inUnit(p.p99Ns())) : "",
                hasPercentiles ? format(row.inUnit(p.p999Ns())) : "",
                hasPercentiles ? format(row.inUnit(p.maxNs())) : "",
                hasPercentiles ? row.unit() : "", figure, row.aim(), row.verdict(),
                row.measured() ? row.note() : "**" + row.note() + "**") + " |";
    }

    private static String format(double value) {
        return value >= 100 ? String.format(Locale.ROOT, "%.0f", value) : String.format(Locale.ROOT, "%.1f", value);
    }

    private static String formatValue(double value) {
        return value >= 1e6 ? String.format(Locale.ROOT, "%.2f M", value / 1e6)
                : value >= 1e4 ? String.format(Locale.ROOT, "%.0f k", value / 1e3) : format(value);
    }
}
