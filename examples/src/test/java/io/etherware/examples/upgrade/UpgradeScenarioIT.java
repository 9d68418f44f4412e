package io.etherware.examples.upgrade;

import static org.junit.jupiter.api.Assertions.assertEquals;
import static org.junit.jupiter.api.Assertions.assertFalse;
import static org.junit.jupiter.api.Assertions.assertTrue;

import io.etherware.examples.scenario.Progress;
import io.etherware.examples.scenario.RunSummary;
import io.etherware.examples.scenario.ScenarioRun;
import io.etherware.pendulum.components.ControlCycle;
import io.etherware.services.management.UpgradeResult;
import java.nio.file.Path;
import java.util.List;
import org.junit.jupiter.api.Test;

/**
 * The upgrade scenario end to end, shortened to 10 s with the upgrade at 5 s: controller V2 is
 * loaded from the plugin jar the build made (package phase, before this test) and replaces V1
 * while the pendulum balances in real time.
 */
class UpgradeScenarioIT {

    private static final long RUN_NS = 10_000_000_000L;

    @Test
    void shouldSwapInV2FromThePluginJarWithoutLettingThePendulumGo() throws Exception {
        Path jar = UpgradeCommand.defaultJar();
        assertUpgradedUpright(UpgradeConfig.of(RUN_NS, UpgradeConfig.DEFAULT_PERIOD_NS, jar,
                Path.of("target", "scenarios-it", "upgrade")));
    }

    /** The paper's topology: the controller in a second JVM, the request from node 1's Requester. */
    @Test
    void shouldSwapInV2OnTheControllersNodeAtTheRequestOfTheRequesterOnThePlantsNode() throws Exception {
        Path jar = UpgradeCommand.defaultJar();
        assertUpgradedUpright(UpgradeConfig.of(RUN_NS, UpgradeConfig.DEFAULT_PERIOD_NS, jar,
                Path.of("target", "scenarios-it", "upgrade-remote")).withRemote(true));
    }

    private static void assertUpgradedUpright(UpgradeConfig config) throws Exception {
        UpgradeOutcome outcome = new UpgradeScenario(config, new Progress("upgrade", RUN_NS / 1e9, System.out, false))
                .run();
        UpgradeReport.write(config, outcome);
        UpgradeReport.upgradeLines(outcome).forEach(System.out::println);
        ScenarioRun run = outcome.run();
        RunSummary whole = RunSummary.of(run);
        System.out.println(whole);

        assertTrue(outcome.upgraded(), () -> "the upgrade failed: " + outcome.failure());
        UpgradeResult result = outcome.result();
        assertEquals(UpgradeConfig.V2_CLASS, result.newImplementation());
        assertTrue(result.source().endsWith(UpgradeConfig.JAR_SUFFIX), () -> "loaded from " + result.source());
        // Upright throughout, V1 and V2 alike.
        assertFalse(whole.fell());
        assertTrue(whole.maxAbsTheta2Rad() < 0.1, () -> "max |θ2| " + whole.maxAbsTheta2Rad());
        // V2's gains run from the hand-over on; V1's never again.
        List<ControlCycle> after = run.cycles().stream().filter(c -> c.releaseNs() >= outcome.v2FromNs()).toList();
        assertTrue(after.size() > 200, () -> "V2 ran " + after.size() + " cycles");
        assertTrue(after.stream().allMatch(c -> c.gainVersion() == 2), "every cycle after the hand-over is V2's");
        // The loop lost nothing: the swap waits until no reading of V1's is in flight, so every
        // cycle ends in a torque command, and the hand-over fits the measured swap gap. A release
        // the Notifier itself skipped (its thread woke too late: a stall, counted) has no cycle.
        UpgradeReport.HandOver handOver = UpgradeReport.handOver(run).orElseThrow();
        assertTrue(handOver.lostCycles() <= outcome.releasesSkipped(), () -> "cycles lost in the hand-over: "
                + handOver.lostCycles() + ", releases skipped by the Notifier in the whole run: "
                + outcome.releasesSkipped());
        assertTrue(result.gapNs() >= 0 && handOver.handOverNs() < result.gapNs() + 2 * run.periodNs(),
                () -> "hand-over " + handOver.handOverNs() + " ns against the swap gap " + result.gapNs() + " ns");
        long missesAfter = RunSummary.of(outcome.afterUpgrade()).deadlineMisses();
        assertTrue(missesAfter <= 0.02 * RunSummary.of(outcome.afterUpgrade()).releases(),
                () -> "V2 missed " + missesAfter + " deadlines");
    }
}
