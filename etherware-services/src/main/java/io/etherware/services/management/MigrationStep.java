package io.etherware.services.management;

import io.etherware.core.component.ComponentState;
import io.etherware.core.message.Contents;
import io.etherware.core.message.Profile;
import java.util.Objects;

/**
 * One step of a migration, sent by the source node's management service to the target's,
 * registered as {@code etherware.migrationStep}; answered with a {@link MigrationStepDone} or a
 * {@link ManagementFailure}. Not for applications: {@link Management#migrate} starts a migration.
 *
 * <p>Immutable; safe to share between threads.
 *
 * @param phase         which step
 * @param target        the exact profile of the component moving
 * @param fromNode      the source node; the target refuses a step whose {@code fromNode} is not the
 *                      node it came from (its origin), and grants nothing for it
 * @param arrival       the profile under which the target receives the messages the source
 *                      forwards (unique to this migration), until and after the hand-over
 * @param className     {@link Phase#PREPARE}: the class to instantiate; otherwise null
 * @param jarPath       {@link Phase#PREPARE}: the jar to load it from, or null for the class path
 * @param configuration {@link Phase#PREPARE}: the constructor's argument, or null
 * @param state         {@link Phase#INSTALL}: the component's state, or null if it has none
 * @param forwarded     {@link Phase#HANDOVER}: how many messages the source forwarded to the
 *                      arrival profile before it; the target admits the component once they are in
 * @param stepTimeoutNs the source's {@code migrationStepTimeout}: how long it waits for the step's
 *                      answer; {@link Phase#INSTALL}: so it resumes the component no sooner than
 *                      this after sending it, which a target taking the component over from a
 *                      source that died counts on (0: not said, for a step that needs no such word)
 */
public record MigrationStep(Phase phase, Profile target, String fromNode, Profile arrival, String className, String jarPath,
                            String configuration, ComponentState state, long forwarded, long stepTimeoutNs)
        implements Contents {

    /**
     * Checks that the fields every phase needs are given.
     *
     * @throws NullPointerException if {@code phase}, {@code target}, {@code fromNode} or
     *                              {@code arrival} is null
     */
    public MigrationStep {
        Objects.requireNonNull(phase, "phase");
        Objects.requireNonNull(target, "target");
        Objects.requireNonNull(fromNode, "fromNode");
        Objects.requireNonNull(arrival, "arrival");
        if (stepTimeoutNs < 0) {
            throw new IllegalArgumentException("stepTimeoutNs=" + stepTimeoutNs + " must not be negative");
        }
    }

    /** The steps, in the order the source sends them. */
    public enum Phase {
        /** Load the class and construct the new instance; nothing is registered yet. */
        PREPARE,
        /** Restore the state into the prepared instance and register it, held, under the arrival profile. */
        INSTALL,
        /**
         * The held messages have been forwarded ahead of this: register the component under its
         * profile and release it.
         */
        HANDOVER
    }
}
