package io.etherware.examples.upgrade;

import io.etherware.examples.scenario.ScenarioRun;
import io.etherware.services.management.UpgradeResult;
import java.util.Objects;

/**
 * What the upgrade scenario recorded: the whole run, and the upgrade's answer or its failure.
 * Immutable.
 *
 * @param run       the run, with the request and the answer as {@code UPGRADE} events
 * @param result    the management service's answer, or null if the upgrade failed
 * @param failure   why it failed, or null
 * @param requestNs when the request was sent, on the node's clock
 * @param v2FromNs  the release of V2's first cycle (the answer's time if V2 never ran)
 * @param answerNs  when the answer (or the failure) came; the service waits for V2's first
 *                  message before it answers, to measure the swap gap
 * @param releasesSkipped the controller's releases the Notifier skipped in the whole run (it woke
 *                  too late, the controller was still busy, or the Tick was undeliverable): no
 *                  Tick went out for them, so they have no cycle
 */
public record UpgradeOutcome(ScenarioRun run, UpgradeResult result, String failure, long requestNs, long v2FromNs,
        long answerNs, long releasesSkipped) {

    public UpgradeOutcome {
        Objects.requireNonNull(run, "run");
        if ((result == null) == (failure == null)) {
            throw new IllegalArgumentException("exactly one of result and failure must be given");
        }
    }

    /** Whether V2 took over. */
    public boolean upgraded() {
        return result != null;
    }

    /** The part of the run before the request: V1. */
    public ScenarioRun beforeUpgrade() {
        return run.slice("v1", "V1 soft, before", run.originNs(), requestNs);
    }

    /** The part of the run from V2's first cycle: V2 (or V1 still, from the answer, if the upgrade failed). */
    public ScenarioRun afterUpgrade() {
        return run.slice("v2", upgraded() ? "V2 tight, after" : "V1 still, after", v2FromNs, run.endNs());
    }
}
