package io.etherware.examples.migrate;

import io.etherware.examples.scenario.ScenarioRun;
import io.etherware.services.management.MigrationResult;
import java.util.Objects;

/**
 * What the migration scenario recorded: the whole run, and the migration's answer or its failure.
 * Immutable.
 *
 * @param run          the run, with the request as a {@code MIGRATION} event
 * @param result       the management service's answer, or null if the migration failed
 * @param failure      why it failed, or null
 * @param requestNs    when the requester sent the request, on the plant node's clock
 * @param answerNs     when the answer (or the failure) came
 * @param handOver     how the control loop crossed from node 2 to node 1, or null if it did not
 * @param finalHost    the node hosting the controller at the end, as node 1's registry says
 * @param releasesSkipped the controller's releases the Notifier skipped in the whole run (it woke
 *                     too late, the controller was still busy, or the Tick was undeliverable): no
 *                     Tick went out for them, so they have no cycle
 */
public record MigrateOutcome(ScenarioRun run, MigrationResult result, String failure, long requestNs, long answerNs,
        HandOver handOver, String finalHost, long releasesSkipped) {

    public MigrateOutcome {
        Objects.requireNonNull(run, "run");
        Objects.requireNonNull(finalHost, "finalHost");
        if ((result == null) == (failure == null)) {
            throw new IllegalArgumentException("exactly one of result and failure must be given");
        }
    }

    /**
     * The control loop across the migration, from the controller's own cycles.
     *
     * @param lastRemoteCycle the last cycle commanded by the instance on node 2
     * @param firstLocalCycle the first cycle commanded by the instance on node 1
     * @param lastRemoteNs    when node 2's last torque command left (its reading came)
     * @param firstLocalNs    when node 1's first torque command left
     */
    public record HandOver(long lastRemoteCycle, long firstLocalCycle, long lastRemoteNs, long firstLocalNs) {

        /** From node 2's last torque command to node 1's first. */
        public long handOverNs() {
            return firstLocalNs - lastRemoteNs;
        }

        /** Releases between the two that got no command. */
        public long lostCycles() {
            return Math.max(0, firstLocalCycle - lastRemoteCycle - 1);
        }
    }

    /**
     * How long the migration kept the component from running: quiesce, transfer and relocate, from
     * the hold at the source until the profile points at the target and the held messages are on
     * their way (the hand-over that releases it there follows in one message). Unlike the
     * {@linkplain MigrationResult#gapNs() gap}, it holds no idle time waiting for the next message.
     */
    public static long pauseNs(MigrationResult result) {
        return result.quiesceNs() + result.transferNs() + result.relocateNs();
    }

    /** Whether the controller moved. */
    public boolean migrated() {
        return result != null;
    }

    /** The part of the run before the request: the controller on node 2. */
    public ScenarioRun beforeMigration() {
        return run.slice("node2", "on node 2, before", run.originNs(), requestNs);
    }

    /** The part of the run from the first cycle on node 1 (from the answer if it never ran there). */
    public ScenarioRun afterMigration() {
        long fromNs = handOver != null ? handOver.firstLocalNs() : answerNs;
        return run.slice("node1", migrated() ? "on node 1, after" : "on node 2 still, after", fromNs, run.endNs());
    }
}
