package io.etherware.examples.netstress;

import io.etherware.examples.output.ComparisonTable;
import io.etherware.examples.scenario.RunSummary;
import io.etherware.examples.scenario.ScenarioRun;
import io.etherware.examples.stress.StressConfig;
import io.etherware.examples.stress.StressReport;
import java.io.IOException;
import java.nio.file.Files;
import java.nio.file.Path;
import java.util.ArrayList;
import java.util.List;
import java.util.Locale;
import java.util.function.Function;

/**
 * The networked stress experiment's table and files: the stress table with rows for each node's
 * scheduler-counted deadline misses, the control cycles lost and the stress activations; per run
 * {@code netstress-<run>.csv} and {@code .png/.svg}, {@code netstress.png/.svg} with the runs overlaid,
 * {@code summary.txt}, and node 2's logs, in the output directory.
 *
 * <p>Stateless and thread-safe.
 */
public final class NetStressReport {

    private NetStressReport() {
    }

    /** The heading line of the table: what ran. */
    public static String heading(StressConfig config, long node2OffsetNs) {
        return String.format(Locale.ROOT, "netstress (paper Section VI-B, Fig. 10 topology): %.0f s per run; DSP board,"
                + " DSPProxy and Notifier on node 1, controller on node 2 (a second JVM) on HIGH Ticks every %d ms"
                + " across TCP on loopback; on each node a stress task on LOW Ticks every %.1f s computing %d ms (node"
                + " 2's %.1f s after node 1's) and %d load threads allocating", config.durationNs() / 1e9,
                config.periodNs() / 1_000_000, config.stressEveryNs() / 1e9, config.stressWorkNs() / 1_000_000,
                node2OffsetNs / 1e9, config.loadThreads()) + StressReport.setup(config);
    }

    /** The side-by-side table of {@code runs} with their {@code summaries}. */
    public static String table(List<NetStressRun> runs, List<RunSummary> summaries) {
        return ComparisonTable.format(runs.stream().map(NetStressRun::run).toList(), summaries, List.of(
                row("node 1 misses (scheduler)", runs, r -> counted(r.node1Misses())),
                row("node 2 misses (scheduler)", runs, r -> counted(r.node2Misses())),
                row("control cycles lost", runs, r -> Long.toString(r.cyclesLost())),
                row("stress activations 1 / 2", runs, r -> r.node1Activations() + " / " + r.node2Activations())));
    }

    /** Writes everything; returns the files written, in order. */
    public static List<Path> write(StressConfig config, long node2OffsetNs, List<NetStressRun> runs,
            List<RunSummary> summaries) throws IOException {
        List<ScenarioRun> scenarioRuns = runs.stream().map(NetStressRun::run).toList();
        List<Path> written = new ArrayList<>(StressReport.write(config.out(), "netstress", "Networked stress",
                heading(config, node2OffsetNs), table(runs, summaries), scenarioRuns));
        for (ScenarioRun run : scenarioRuns) {
            Path log = config.out().resolve("node-2-" + run.key() + ".log");
            if (Files.exists(log)) {
                written.add(log);
            }
        }
        return written;
    }

    private static ComparisonTable.Row row(String label, List<NetStressRun> runs, Function<NetStressRun, String> cell) {
        return new ComparisonTable.Row(label, runs.stream().map(cell).toList());
    }

    private static String counted(long misses) {
        return misses == NetStressRun.NOT_COUNTED ? "not counted" : Long.toString(misses);
    }
}
