package io.etherware.examples.migrate;

import static org.junit.jupiter.api.Assertions.assertEquals;
import static org.junit.jupiter.api.Assertions.assertFalse;
import static org.junit.jupiter.api.Assertions.assertNotNull;
import static org.junit.jupiter.api.Assertions.assertTrue;

import io.etherware.examples.scenario.Progress;
import io.etherware.examples.scenario.RunSummary;
import io.etherware.examples.scenario.ScenarioRun;
import io.etherware.examples.scenario.StolenTime;
import io.etherware.pendulum.components.ControlCycle;
import io.etherware.pendulum.components.PendulumController;
import io.etherware.services.management.MigrationResult;
import java.nio.file.Files;
import java.nio.file.Path;
import org.junit.jupiter.api.Test;

/**
 * The migration scenario end to end with two real JVMs, shortened to 12 s with the migration at
 * 8 s: the controller starts on node 2 (a second JVM on this class path), balances the pendulum
 * through the DSPProxy on node 1 over TCP, and moves to node 1 while it balances.
 */
class MigrateScenarioIT {

    private static final long RUN_NS = 12_000_000_000L;
    private static final long MIGRATE_AT_NS = 8_000_000_000L;

    /** One run of the scenario, and the CPU time the hypervisor took meanwhile. */
    private record Attempt(MigrateOutcome outcome, long stolenMs, RunSummary whole) {
    }

    private static Attempt attempt(MigrateConfig config) throws Exception {
        long stolenBeforeMs = StolenTime.sinceBootMs();
        MigrateOutcome outcome = new MigrateScenario(config, new Progress("migrate", RUN_NS / 1e9, System.out, false))
                .run();
        long stolenMs = StolenTime.sinceBootMs() - stolenBeforeMs;
        MigrateReport.write(config, outcome);
        MigrateReport.migrationLines(outcome).forEach(System.out::println);
        RunSummary whole = RunSummary.of(outcome.run());
        System.out.println(whole);
        return new Attempt(outcome, stolenMs, whole);
    }

    @Test
    void shouldMoveTheControllerToTheDspProxysNodeWithoutLettingThePendulumGo() throws Exception {
        MigrateConfig config = MigrateConfig.of(RUN_NS, 15_000_000L, Path.of("target", "scenarios-it", "migrate"))
                .withMigrateAtNs(MIGRATE_AT_NS);
        Attempt attempt = attempt(config);
        if (attempt.whole().fell() && attempt.whole().fellAtS() * 1e9 < MIGRATE_AT_NS) {
            // A second run, once, for a fall before the migration (which this test is about): in
            // 2 of 8 starts of two-JVM scenarios one day, node 1's DSP board (SCHED_FIFO 90) and
            // its Notifier (82) each ran at full CPU for about a second as the board started, the
            // first-use stall of two real-time threads on two cores (docs/REALTIME.md), and the
            // plant fell before any migration. A broken loop falls on both runs.
            System.out.println("the first run fell before the migration: " + attempt.outcome().run().notes());
            attempt = attempt(config);
        }
        MigrateOutcome outcome = attempt.outcome();
        long stolenMs = attempt.stolenMs();
        ScenarioRun run = outcome.run();
        RunSummary whole = attempt.whole();

        assertTrue(outcome.migrated(), () -> "the migration failed: " + outcome.failure()
                + "; node 2's log: " + config.out().resolve("node-2.log"));
        MigrationResult result = outcome.result();
        assertEquals(PendulumController.DEFAULT_PROFILE, result.target());
        assertEquals(MigrateConfig.CONTROL_NODE, result.fromNode());
        assertEquals(MigrateConfig.PLANT_NODE, result.toNode());
        // The controller ends on node 1: its profile resolves to a component of node 1 there.
        assertEquals(MigrateConfig.PLANT_NODE, outcome.finalHost());
        // Upright throughout, on node 2 and on node 1 alike.
        // A fall says which stalled: the plant's own thread (the board's lag: the machine or a JVM
        // safepoint), the machine (time the hypervisor took), or the control loop (neither).
        assertFalse(whole.fell(), () -> "the pendulum fell at " + whole.fellAtS() + " s; the hypervisor took "
                + stolenMs + " ms of CPU time during the run; " + run.notes());
        assertTrue(whole.maxAbsTheta2Rad() < 0.2, () -> "max |θ2| " + whole.maxAbsTheta2Rad());
        // Both instances controlled: node 2 before, node 1 after, with cycles from both.
        MigrateOutcome.HandOver handOver = outcome.handOver();
        assertNotNull(handOver, "node 1's instance commanded no torque");
        long beforeCycles = run.cycles().stream().filter(c -> c.cycle() <= handOver.lastRemoteCycle()
                && c.outcome() == ControlCycle.Outcome.COMMANDED).count();
        assertTrue(beforeCycles > 0.8 * MIGRATE_AT_NS / run.periodNs(), () -> "node 2 commanded only " + beforeCycles
                + " cycles before the migration");
        // The controller paused for less than one control period, and the loop lost no cycle: the
        // hold waits until the reading in flight has reached the controller on node 2, so no reply
        // is left behind there. The gap is reported, not asserted: it includes the wait for the
        // next Tick, so it depends on where in the period the hold fell.
        long pauseNs = MigrateOutcome.pauseNs(result);
        assertTrue(result.gapNs() >= 0 && pauseNs < run.periodNs(),
                () -> "paused " + pauseNs + " ns (gap " + result.gapNs() + " ns), control period " + run.periodNs()
                        + " ns");
        // A release the Notifier itself skipped (its thread woke too late: a stall of the JVM or the
        // machine, counted) has no Tick and so no cycle; any other missing cycle is the migration's.
        assertTrue(handOver.lostCycles() <= outcome.releasesSkipped(), () -> handOver.lostCycles()
                + " cycles without a command across the migration, " + outcome.releasesSkipped()
                + " releases skipped by the Notifier in the whole run; the cycles"
                + " around it (a cycle missing here had no Tick handled): " + run.cycles().stream()
                .filter(c -> c.cycle() >= handOver.lastRemoteCycle() - 1 && c.cycle() <= handOver.firstLocalCycle() + 1)
                .map(c -> c.cycle() + " " + c.outcome() + " released " + c.releaseNs() + " started +"
                        + (c.startNs() - c.releaseNs()) + " read +" + (c.readoutNs() - c.releaseNs()) + " ns")
                .toList() + "; node 1's summary: " + config.out().resolve("summary.txt"));
        assertTrue(Files.size(config.out().resolve("migrate.csv")) > 0, "the CSV was written");
    }
}
