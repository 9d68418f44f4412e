package io.etherware.examples.output;

import io.etherware.examples.scenario.RunSummary;
import io.etherware.examples.scenario.ScenarioRun;
import java.util.ArrayList;
import java.util.List;
import java.util.Locale;
import java.util.Objects;
import java.util.function.Function;

/**
 * The side-by-side table of a scenario's runs (paper Section VI-B): one column per run, one row
 * per figure of {@link RunSummary}.
 *
 * <pre>
 *                                original Etherware   Etherware-RT
 * max |θ2| (rad)                             3.1416         0.0231
 * ...
 * </pre>
 *
 * <p>Stateless and thread-safe.
 */
public final class ComparisonTable {

    private static final int LABEL_WIDTH = 30;
    private static final int MIN_COLUMN_WIDTH = 20;

    private ComparisonTable() {
    }

    /** The table of {@code runs} with their {@code summaries} (same order), lines ending in '\n'. */
    public static String format(List<ScenarioRun> runs, List<RunSummary> summaries) {
        return format(runs, summaries, List.of());
    }

    /**
     * A row a scenario adds below the summary's: a label and one cell per run, in the runs' order.
     *
     * @param label what the row shows, with its unit
     * @param cells one per run
     */
    public record Row(String label, List<String> cells) {
        public Row {
            Objects.requireNonNull(label, "label");
            cells = List.copyOf(cells);
        }
    }

    /** The table of {@code runs} with their {@code summaries} and a scenario's {@code extra} rows below. */
    public static String format(List<ScenarioRun> runs, List<RunSummary> summaries, List<Row> extra) {
        if (runs.size() != summaries.size()) {
            throw new IllegalArgumentException("runs=" + runs.size() + " but summaries=" + summaries.size());
        }
        for (Row row : extra) {
            if (row.cells().size() != runs.size()) {
                throw new IllegalArgumentException("row '" + row.label() + "' has " + row.cells().size()
                        + " cells for " + runs.size() + " runs");
            }
        }
        int width = Math.max(MIN_COLUMN_WIDTH, runs.stream().mapToInt(r -> r.title().length() + 2).max().orElse(0));
        var text = new StringBuilder();
        text.append(" ".repeat(LABEL_WIDTH));
        runs.forEach(run -> text.append(pad(run.title(), width)));
        text.append('\n');
        row(text, "max |θ2| (rad)", summaries, s -> f("%.4f", s.maxAbsTheta2Rad()), width);
        row(text, "RMS θ2 (rad)", summaries, s -> f("%.4f", s.rmsTheta2Rad()), width);
        row(text, "RMS θ1 (rad)", summaries, s -> f("%.4f", s.rmsTheta1Rad()), width);
        row(text, "period jitter p50 (ms)", summaries, s -> f("%.3f", s.jitterP50Ms()), width);
        row(text, "period jitter p99 (ms)", summaries, s -> f("%.3f", s.jitterP99Ms()), width);
        row(text, "period jitter max (ms)", summaries, s -> f("%.3f", s.jitterMaxMs()), width);
        row(text, "deadline misses", summaries, s -> s.deadlineMisses() + " of " + s.releases(), width);
        row(text, "fell (|θ2| > " + RunSummary.FALL_THRESHOLD_RAD + " rad)", summaries,
                s -> s.fell() ? f("yes, at %.2f s", s.fellAtS()) : "no", width);
        for (Row row : extra) {
            text.append(String.format(Locale.ROOT, "%-" + LABEL_WIDTH + "s", row.label()));
            row.cells().forEach(cell -> text.append(pad(cell, width)));
            text.append('\n');
        }
        return text.toString();
    }

    /** The table's rows as a list, for logs. */
    public static List<String> lines(List<ScenarioRun> runs, List<RunSummary> summaries) {
        return new ArrayList<>(List.of(format(runs, summaries).split("\n")));
    }

    private static void row(StringBuilder text, String label, List<RunSummary> summaries,
            Function<RunSummary, String> cell, int width) {
        text.append(String.format(Locale.ROOT, "%-" + LABEL_WIDTH + "s", label));
        summaries.forEach(summary -> text.append(pad(cell.apply(summary), width)));
        text.append('\n');
    }

    private static String pad(String cell, int width) {
        return " ".repeat(Math.max(1, width - cell.length())) + cell;
    }

    private static String f(String format, double value) {
        return Double.isNaN(value) ? "-" : String.format(Locale.ROOT, format, value);
    }
}
