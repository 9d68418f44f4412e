package io.etherware.services.management;

import io.etherware.core.message.Contents;
import io.etherware.core.message.Profile;
import java.util.Objects;

/**
 * The answer to a management request that was refused or failed, registered as
 * {@code etherware.managementFailure}. Whatever the reason, the component kept its old logic (an
 * upgrade) or resumed where it was (a migration), and no message to it was lost.
 *
 * <p>Immutable; safe to share between threads.
 *
 * @param operation what was asked, e.g. {@code upgrade}, {@code migrate}, or a migration step
 * @param target    the component's profile as the request named it
 * @param reason    the kind of failure
 * @param error     what went wrong, naming the offending value and, where there is one, the fix
 */
public record ManagementFailure(String operation, Profile target, Reason reason, String error) implements Contents {

    /**
     * Checks that every field is given.
     *
     * @throws NullPointerException if a field is null
     */
    public ManagementFailure {
        Objects.requireNonNull(operation, "operation");
        Objects.requireNonNull(target, "target");
        Objects.requireNonNull(reason, "reason");
        Objects.requireNonNull(error, "error");
    }

    /** Why a management request failed. */
    public enum Reason {
        /**
         * The request (or a migration step, or a step's answer) came from another node and this
         * node's access list does not let that node ask for it, or it came through a relay, or
         * over an unauthenticated link (see {@link ManagementConfig}).
         */
        REMOTE_REFUSED,
        /** The request was malformed (e.g. a class name that is not a binary name). */
        BAD_REQUEST,
        /** No local component matches the profile (or it is hosted on another node). */
        UNKNOWN_COMPONENT,
        /**
         * The node's management service has as many operations waiting as it queues
         * ({@link ManagementConfig.Builder#maxQueuedOperations}): nothing was done; ask again later.
         */
        BUSY,
        /** The component is not running (failed, stopped), so it cannot be upgraded. */
        NOT_RUNNING,
        /** The jar is outside the allowlisted directories. */
        CODE_NOT_ALLOWED,
        /**
         * The jar is not signed, only partly signed, signed by a key the node does not trust, or
         * changed after signing; or the node trusts no signer at all (see {@link ManagementConfig}).
         */
        UNTRUSTED_CODE,
        /** The class or the jar could not be found or loaded. */
        CLASS_NOT_LOADABLE,
        /** The class breaks the implementation contract (see {@link Implementation}). */
        INVALID_IMPLEMENTATION,
        /** The class's constructor or static initializer threw. */
        CONSTRUCTION_FAILED,
        /**
         * The new logic's {@code restore} or {@code onStart} threw (for a migration: the
         * snapshot at the source, or {@code restore} or {@code onStart} at the target); the old
         * logic resumed.
         */
        ROLLED_BACK,
        /**
         * The target node of a migration is not connected, refused nothing but did not answer a
         * step in time, or went away; the component resumed at the source.
         */
        TARGET_UNREACHABLE,
        /** The management service is stopping or failed unexpectedly. */
        SERVICE_FAILED
    }
}
