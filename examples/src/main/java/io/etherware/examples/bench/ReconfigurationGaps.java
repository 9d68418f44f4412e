package io.etherware.examples.bench;

import java.util.ArrayList;
import java.util.List;

/**
 * Section 6: the reconfiguration gaps, one row per {@link GapMeasurement}. Migration between nodes
 * is not in this build yet; its row says so until a {@link GapMeasurement} for it replaces the
 * placeholder in {@link #defaults()}. Runs on the caller's thread.
 */
final class ReconfigurationGaps {

    private final List<GapMeasurement> measurements;

    ReconfigurationGaps(List<GapMeasurement> measurements) {
        this.measurements = List.copyOf(measurements);
    }

    /** The upgrade gap, and migration as "not measured". */
    static ReconfigurationGaps defaults() {
        return new ReconfigurationGaps(List.of(new UpgradeGap(),
                GapMeasurement.notAvailable("migration", "migration between nodes", "p99 <= 5 ms",
                        "not measured: migration not available")));
    }

    List<BenchRow> measure(BenchConfig config) throws Exception {
        var rows = new ArrayList<BenchRow>();
        for (GapMeasurement measurement : measurements) {
            rows.add(measurement.measure(config, config.upgradeRepetitions()));
        }
        return rows;
    }
}
