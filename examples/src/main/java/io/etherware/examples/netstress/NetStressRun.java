package io.etherware.examples.netstress;

import io.etherware.examples.scenario.RunSummary;
import io.etherware.examples.scenario.ScenarioRun;
import io.etherware.pendulum.components.ControlCycle;
import java.util.Objects;

/**
 * One run of the networked stress experiment: the run as node 1 recorded it (the plant's ground
 * truth and the controller's cycles, which node 2 reported), and what each node's scheduler
 * counted. Immutable.
 *
 * @param run              the run
 * @param node1Misses      node 1's scheduler-counted deadline misses, or {@link #NOT_COUNTED}
 * @param node2Misses      node 2's, or {@link #NOT_COUNTED}
 * @param node1Activations stress activations on node 1
 * @param node2Activations stress activations on node 2
 */
public record NetStressRun(ScenarioRun run, long node1Misses, long node2Misses, long node1Activations,
        long node2Activations) {

    /** The scheduler does not count deadline misses: the original Etherware's FIFO dispatcher. */
    public static final long NOT_COUNTED = Results.NOT_COUNTED;

    public NetStressRun {
        Objects.requireNonNull(run, "run");
    }

    /**
     * Control cycles lost: releases whose deadline passed during the run without any torque
     * command for them, late or not (their Tick skipped or stuck, their reading failed). The
     * deadline misses of {@link RunSummary} also count commands that came too late.
     */
    public long cyclesLost() {
        long releases = RunSummary.releasesDue(run.firstReleaseNs(), run.endNs(), run.periodNs());
        long lastDueReleaseNs = run.firstReleaseNs() + (releases - 1) * run.periodNs();
        long commanded = run.cycles().stream()
                .filter(c -> c.releaseNs() <= lastDueReleaseNs && c.outcome() == ControlCycle.Outcome.COMMANDED)
                .mapToLong(ControlCycle::cycle).distinct().count();
        return Math.max(0, releases - commanded);
    }
}
