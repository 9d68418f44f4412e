package io.etherware.services.management;

import io.etherware.core.message.Contents;
import io.etherware.core.message.Profile;

/**
 * The answer to a successful {@link MigrateRequest}, registered as {@code etherware.migrationResult}:
 * where the component went and how long each phase took, in nanoseconds of the source node's
 * monotonic clock. A duration that could not be measured is -1.
 *
 * <p>The phases, in order: {@code prepare} (the target loads the class and constructs the
 * instance; the component runs on meanwhile), {@code quiesce} (until the component is at a
 * message boundary and held: its last message at the source is done), {@code transfer} (snapshot,
 * the state as XML to the target, {@code restore} and registration there, the target's answer),
 * {@code relocate} (the profile is pointed at the target and the held messages are forwarded).
 * The gap runs from the quiesce (the end of the last message handled at the source, under a
 * steady stream) to the start of the first message handled at the target; the target's time is
 * translated into the source's clock by NetworkTime, so across hosts it carries the offset
 * estimate's error. It includes any time in which no message was waiting.
 *
 * <p>Immutable; safe to share between threads.
 *
 * @param target             the exact profile of the component moved
 * @param fromNode           the node it left
 * @param toNode             the node it runs on now
 * @param implementation     the class name of the logic running at the target
 * @param stateSchemaVersion the schema version of the state shipped, or -1 if the component had none
 * @param heldMessages       messages held at the source during the move and forwarded to the target
 * @param prepareNs          request to the target to load and construct, until its answer
 * @param quiesceNs          hold requested until the component is held at a message boundary
 * @param transferNs         snapshot, install at the target, until its answer
 * @param relocateNs         pointing the profile at the target and forwarding the held messages
 * @param gapNs              last message handled at the source to the first handled at the target;
 *                           -1 if no message reached the target within the service's wait for it
 * @param totalNs            from the request's arrival at the source's management service to the
 *                           target's answer to the hand-over
 */
public record MigrationResult(Profile target, String fromNode, String toNode, String implementation,
                              int stateSchemaVersion, long heldMessages, long prepareNs,
                              long quiesceNs, long transferNs, long relocateNs, long gapNs, long totalNs)
        implements Contents {
}
