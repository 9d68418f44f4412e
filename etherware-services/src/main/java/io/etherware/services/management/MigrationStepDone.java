package io.etherware.services.management;

import io.etherware.core.message.Contents;
import io.etherware.core.message.Profile;

/**
 * The target's answer to a successful {@link MigrationStep}, registered as
 * {@code etherware.migrationStepDone}. Not for applications.
 *
 * <p>Immutable; safe to share between threads.
 *
 * @param phase                the step done
 * @param target               the component's profile
 * @param implementation       the class of the instance at the target
 * @param workNs               the target's own work for the step (load and construct; restore and
 *                             register), in its clock; -1 for the hand-over
 * @param firstHandlingEpochNs {@link MigrationStep.Phase#HANDOVER}: when the component's first
 *                             message at the target began, in the target's epoch clock; -1 if no
 *                             message came within the target's wait, or for other steps
 */
public record MigrationStepDone(MigrationStep.Phase phase, Profile target, String implementation, long workNs,
                                long firstHandlingEpochNs) implements Contents {
}
