package io.etherware.examples.bench;

import java.util.ArrayList;
import java.util.List;

/**
 * Section 6: the reconfiguration gaps, one row per {@link GapMeasurement}: the upgrade and the
 * migration between nodes. Runs on the caller's thread.
 */
final class ReconfigurationGaps {

    private final List<GapMeasurement> measurements;

    ReconfigurationGaps(List<GapMeasurement> measurements) {
        this.measurements = List.copyOf(measurements);
    }

    /** The upgrade gap and the migration gap. */
    static ReconfigurationGaps defaults() {
        return new ReconfigurationGaps(List.of(new UpgradeGap(), new MigrationGap()));
    }

    List<BenchRow> measure(BenchConfig config) throws Exception {
        var rows = new ArrayList<BenchRow>();
        for (GapMeasurement measurement : measurements) {
            rows.add(measurement.measure(config, config.upgradeRepetitions()));
        }
        return rows;
    }
}
