package io.etherware.examples.upgrade;

import io.etherware.examples.output.PhaseReport;
import io.etherware.examples.scenario.ScenarioRun;
import io.etherware.pendulum.components.ControlCycle;
import io.etherware.services.management.UpgradeResult;
import java.io.IOException;
import java.nio.file.Path;
import java.util.ArrayList;
import java.util.Comparator;
import java.util.List;
import java.util.Locale;
import java.util.Optional;

/**
 * The upgrade scenario's figures and files: the table of V1 before and V2 after the upgrade, the
 * upgrade's timings as the management service measured them, the control hand-over as the
 * controller's cycles show it, and {@code upgrade.csv}, {@code upgrade.png/.svg} and
 * {@code summary.txt} in the output directory.
 *
 * <p>Stateless and thread-safe.
 */
public final class UpgradeReport {

    private UpgradeReport() {
    }

    /**
     * How the loop crossed the upgrade, from the controller's own cycles: the last torque command
     * computed with V1's gains and the first with V2's.
     *
     * @param lastV1       V1's last commanded cycle
     * @param firstV2      V2's first commanded cycle
     * @param handOverNs   from V1's last command to V2's first
     * @param lostCycles   releases between them that got no command
     */
    public record HandOver(ControlCycle lastV1, ControlCycle firstV2, long handOverNs, long lostCycles) {
    }

    /** The hand-over, if both versions commanded at least once. */
    public static Optional<HandOver> handOver(ScenarioRun run) {
        List<ControlCycle> commanded = run.cycles().stream()
                .filter(c -> c.outcome() == ControlCycle.Outcome.COMMANDED)
                .sorted(Comparator.comparingLong(ControlCycle::readoutNs)).toList();
        Optional<ControlCycle> lastV1 = commanded.stream().filter(c -> c.gainVersion() == 1).reduce((a, b) -> b);
        Optional<ControlCycle> firstV2 = commanded.stream().filter(c -> c.gainVersion() == 2).findFirst();
        if (lastV1.isEmpty() || firstV2.isEmpty()) {
            return Optional.empty();
        }
        ControlCycle before = lastV1.get();
        ControlCycle after = firstV2.get();
        return Optional.of(new HandOver(before, after, after.readoutNs() - before.readoutNs(),
                Math.max(0, after.cycle() - before.cycle() - 1)));
    }

    /** The heading line: what ran. */
    public static String heading(UpgradeConfig config) {
        return String.format(Locale.ROOT, "upgrade (paper Section VI-C1): %.0f s on Etherware-RT, controller on HIGH"
                + " Ticks every %d ms; V1 (soft gains) replaced by V2 (tight gains, from %s) at t = %.1f s by a HIGH"
                + " management request%s", config.durationNs() / 1e9, config.periodNs() / 1_000_000,
                config.jar().getFileName(), config.upgradeAtNs() / 1e9, config.remote()
                        ? " from the Requester on node 1 to the controller's node 2 (a second JVM), as in Fig. 10"
                        : " on the one node");
    }

    /** The lines about the upgrade itself: what replaced what, its timings and the hand-over. */
    public static List<String> upgradeLines(UpgradeOutcome outcome) {
        List<String> lines = new ArrayList<>();
        ScenarioRun run = outcome.run();
        if (!outcome.upgraded()) {
            lines.add(String.format(Locale.ROOT, "upgrade requested at %.2f s FAILED: %s; V1 served on",
                    run.secondsOf(outcome.requestNs()), outcome.failure()));
            return lines;
        }
        UpgradeResult result = outcome.result();
        lines.add(String.format(Locale.ROOT, "upgrade requested at %.2f s: %s replaced by %s from %s (state schema %d)",
                run.secondsOf(outcome.requestNs()), simpleName(result.oldImplementation()),
                simpleName(result.newImplementation()), result.source(), result.stateSchemaVersion()));
        lines.add(String.format(Locale.ROOT, "  management service: load %s, pause %s, swap gap %s (last message"
                + " to V1 → first to V2), request to answer %s", ms(result.loadNs()), ms(result.pauseNs()),
                ms(result.gapNs()), ms(outcome.answerNs() - outcome.requestNs())));
        handOver(run).ifPresentOrElse(h -> lines.add(String.format(Locale.ROOT, "  control loop: V1's last torque"
                + " command (cycle %d) → V2's first (cycle %d): %s, control period %s; cycles without a command"
                + " between them: %d", h.lastV1().cycle(), h.firstV2().cycle(), ms(h.handOverNs()),
                ms(run.periodNs()), h.lostCycles())),
                () -> lines.add("  control loop: no torque command from V2 was recorded"));
        handOver(run).ifPresent(h -> lines.addAll(betweenLines(run, h)));
        return lines;
    }

    /**
     * One line for each cycle the hand-over lost: what the controller recorded of it (a reading
     * that failed, and which version waited for it), or that it recorded nothing (the Tick was
     * never released, or a later Tick abandoned it while its reading was out).
     */
    static List<String> betweenLines(ScenarioRun run, HandOver handOver) {
        List<String> lines = new ArrayList<>();
        for (long cycle = handOver.lastV1().cycle() + 1; cycle < handOver.firstV2().cycle(); cycle++) {
            long number = cycle;
            List<ControlCycle> records = run.cycles().stream().filter(c -> c.cycle() == number).toList();
            if (records.isEmpty()) {
                lines.add(String.format(Locale.ROOT, "    cycle %d: no record (not released, or abandoned by the"
                        + " next Tick)", cycle));
            }
            for (ControlCycle c : records) {
                lines.add(String.format(Locale.ROOT, "    cycle %d: %s by V%d, released at %.4f s, started %s"
                        + " late, reading ended %s after the release", cycle, c.outcome(), c.gainVersion(),
                        run.secondsOf(c.releaseNs()), ms(c.startLatenessNs()), ms(c.responseNs())));
            }
        }
        return lines;
    }

    /** The report: V1 before the upgrade against V2 after it, and the upgrade's lines. */
    public static PhaseReport report(UpgradeConfig config, UpgradeOutcome outcome) {
        return new PhaseReport(heading(config), outcome.run(),
                List.of(outcome.beforeUpgrade(), outcome.afterUpgrade()), upgradeLines(outcome));
    }

    /** Writes the CSV, the summary and the plot; returns the files written. */
    public static List<Path> write(UpgradeConfig config, UpgradeOutcome outcome) throws IOException {
        return report(config, outcome).write(config.out(), "upgrade", String.format(Locale.ROOT,
                "Upgrade V1 (soft) → V2 (tight) at %.0f s", outcome.run().secondsOf(outcome.requestNs())));
    }

    private static String simpleName(String className) {
        return className.substring(className.lastIndexOf('.') + 1);
    }

    private static String ms(long nanos) {
        return nanos < 0 ? "n/a" : String.format(Locale.ROOT, "%.3f ms", nanos / 1e6);
    }
}
