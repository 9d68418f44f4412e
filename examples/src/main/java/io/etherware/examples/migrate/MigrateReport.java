package io.etherware.examples.migrate;

import io.etherware.examples.output.AnglePlots;
import io.etherware.examples.output.ComparisonTable;
import io.etherware.examples.output.TraceCsv;
import io.etherware.examples.scenario.RunSummary;
import io.etherware.examples.scenario.ScenarioRun;
import io.etherware.services.management.MigrationResult;
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
 * The migration scenario's figures and files: the table of the controller on node 2 before and on
 * node 1 after the migration, the migration's phases as the management services measured them,
 * the control hand-over as the controller's cycles show it, and {@code migrate.csv},
 * {@code migrate.png/.svg} and {@code summary.txt} in the output directory.
 *
 * <p>Stateless and thread-safe.
 */
public final class MigrateReport {

    private static final Logger LOG = LoggerFactory.getLogger(MigrateReport.class);
    private static final double PLOT_RANGE_RAD = 0.1;

    private MigrateReport() {
    }

    /** The heading line: what ran. */
    public static String heading(MigrateConfig config) {
        return String.format(Locale.ROOT, "migrate (paper Section VI-C2): %.0f s on Etherware-RT in two JVMs, controller"
                + " on HIGH Ticks every %d ms; moved from %s to %s (the node with the DSPProxy) at t = %.1f s by a"
                + " HIGH management request", config.durationNs() / 1e9, config.periodNs() / 1_000_000,
                MigrateConfig.CONTROL_NODE, MigrateConfig.PLANT_NODE, config.migrateAtNs() / 1e9);
    }

    /** The lines about the migration itself: its phases, its gap and the control hand-over. */
    public static List<String> migrationLines(MigrateOutcome outcome) {
        List<String> lines = new ArrayList<>();
        ScenarioRun run = outcome.run();
        if (!outcome.migrated()) {
            lines.add(String.format(Locale.ROOT, "migration requested at %.2f s FAILED: %s; the controller ran on at %s",
                    run.secondsOf(outcome.requestNs()), outcome.failure(), MigrateConfig.CONTROL_NODE));
            return lines;
        }
        MigrationResult result = outcome.result();
        lines.add(String.format(Locale.ROOT, "migration requested at %.2f s: %s moved from %s to %s as %s (state"
                + " schema %d, %d messages held and forwarded); the controller is now on %s",
                run.secondsOf(outcome.requestNs()), result.target(), result.fromNode(), result.toNode(),
                simpleName(result.implementation()), result.stateSchemaVersion(), result.heldMessages(),
                outcome.finalHost()));
        lines.add(String.format(Locale.ROOT, "  management services: prepare %s, quiesce %s, transfer %s, relocate %s"
                + " (the controller paused %s, quiesce to relocate); migration gap %s"
                + " (last message at node 2 → first at node 1, idle time included), request to answer %s",
                ms(result.prepareNs()), ms(result.quiesceNs()), ms(result.transferNs()), ms(result.relocateNs()),
                ms(MigrateOutcome.pauseNs(result)), ms(result.gapNs()), ms(outcome.answerNs() - outcome.requestNs())));
        MigrateOutcome.HandOver handOver = outcome.handOver();
        lines.add(handOver == null ? "  control loop: no torque command from node 1 was recorded"
                : String.format(Locale.ROOT, "  control loop: node 2's last torque command (cycle %d) → node 1's first"
                        + " (cycle %d): %s, control period %s; cycles without a command between them: %d",
                        handOver.lastRemoteCycle(), handOver.firstLocalCycle(), ms(handOver.handOverNs()),
                        ms(run.periodNs()), handOver.lostCycles()));
        return lines;
    }

    /** Writes the CSV, the summary and the plot; returns the files written. */
    public static List<Path> write(MigrateConfig config, MigrateOutcome outcome) throws IOException {
        Path out = config.out();
        Files.createDirectories(out);
        List<Path> written = new ArrayList<>();
        ScenarioRun run = outcome.run();
        Path csv = out.resolve("migrate.csv");
        TraceCsv.write(run, csv);
        written.add(csv);

        List<ScenarioRun> phases = List.of(outcome.beforeMigration(), outcome.afterMigration());
        var text = new StringBuilder(heading(config)).append("\n\n")
                .append(ComparisonTable.format(phases, phases.stream().map(RunSummary::of).toList())).append('\n');
        migrationLines(outcome).forEach(line -> text.append(line).append('\n'));
        text.append('\n');
        run.notes().forEach(note -> text.append(note).append('\n'));
        Path summary = out.resolve("summary.txt");
        Files.writeString(summary, text, StandardCharsets.UTF_8);
        written.add(summary);

        try {
            written.addAll(AnglePlots.save(AnglePlots.jointAngles(run, String.format(Locale.ROOT,
                    "Migration node 2 → node 1 at %.0f s: joint angles", run.secondsOf(outcome.requestNs())),
                    PLOT_RANGE_RAD), out.resolve("migrate")));
        } catch (IOException | RuntimeException | LinkageError | AWTError e) {
            LOG.error("could not draw the plot ({}); the CSV and summary are complete", e.toString(), e);
        }
        Path nodeLog = out.resolve("node-2.log");
        if (Files.exists(nodeLog)) {
            written.add(nodeLog);
        }
        return written;
    }

    private static String simpleName(String className) {
        return className.substring(className.lastIndexOf('.') + 1);
    }

    private static String ms(long nanos) {
        return nanos < 0 ? "n/a" : String.format(Locale.ROOT, "%.3f ms", nanos / 1e6);
    }
}
