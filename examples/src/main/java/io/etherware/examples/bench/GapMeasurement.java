package io.etherware.examples.bench;

import java.util.Locale;

/**
 * One kind of reconfiguration gap for section 6: how long a component's messages stop while it is
 * replaced (upgrade) or moved (migration). Each measurement gives one report row; add one to
 * {@link ReconfigurationGaps} to add a row.
 *
 * <p>{@link #measure} runs on the bench's main thread and may start and stop its own threads and
 * nodes; it must leave nothing running.
 */
public interface GapMeasurement {

    /** The report section of every gap row. */
    String SECTION = "6. reconfiguration gap";

    /** Short stable id, e.g. {@code upgrade}; the row's id is {@code gap.<id>}. */
    String id();

    /** Measures {@code repetitions} gaps (after its own warm-up) and returns the row. */
    BenchRow measure(BenchConfig config, int repetitions) throws Exception;

    /** The row of a measured gap distribution, judged against {@code aimP99Us}. */
    static BenchRow row(String id, String variant, String condition, Percentiles gapsNs, double aimP99Us,
                        String note) {
        BenchRow row = BenchRow.latency("gap." + id, SECTION, variant, condition, "us", gapsNs, note);
        return row.judged(String.format(Locale.ROOT, "p99 <= %s", aimP99Us >= 1000
                ? String.format(Locale.ROOT, "%.0f ms", aimP99Us / 1000) : String.format(Locale.ROOT, "%.0f us",
                aimP99Us)), row.p99() <= aimP99Us);
    }
}
