package io.etherware.examples.migrate;

import io.etherware.examples.output.PhaseReport;
import io.etherware.examples.scenario.ScenarioRun;
import io.etherware.services.management.MigrationResult;
import java.io.IOException;
import java.nio.file.Files;
import java.nio.file.Path;
import java.util.ArrayList;
import java.util.List;
import java.util.Locale;

/**
 * The migration scenario's figures and files: the table of the controller on node 2 before and on
 * node 1 after the migration, the migration's phases as the management services measured them,
 * the control hand-over as the controller's cycles show it, and {@code migrate.csv},
 * {@code migrate.png/.svg} and {@code summary.txt} in the output directory.
 *
 * <p>Stateless and thread-safe.
 */
public final class MigrateReport {

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

    /** The report: the controller on node 2 before the migration against node 1 after it, and the migration's lines. */
    public static PhaseReport report(MigrateConfig config, MigrateOutcome outcome) {
        return new PhaseReport(heading(config), outcome.run(),
                List.of(outcome.beforeMigration(), outcome.afterMigration()), migrationLines(outcome));
    }

    /** Writes the CSV, the summary, the plot and node 2's log; returns the files written. */
    public static List<Path> write(MigrateConfig config, MigrateOutcome outcome) throws IOException {
        List<Path> written = new ArrayList<>(report(config, outcome).write(config.out(), "migrate",
                String.format(Locale.ROOT, "Migration node 2 → node 1 at %.0f s",
                        outcome.run().secondsOf(outcome.requestNs()))));
        Path nodeLog = config.out().resolve("node-2.log");
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
