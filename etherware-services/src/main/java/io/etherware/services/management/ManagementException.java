package io.etherware.services.management;

import java.util.Objects;

/**
 * A refused or failed management operation, as the {@link Management} client's futures report it:
 * carries the node's {@link ManagementFailure}.
 *
 * <p>Immutable; safe to share between threads.
 */
public final class ManagementException extends RuntimeException {

    private final ManagementFailure failure;

    public ManagementException(ManagementFailure failure) {
        super(failure.operation() + " of '" + failure.target() + "' failed (" + failure.reason() + "): "
                + failure.error());
        this.failure = Objects.requireNonNull(failure, "failure");
    }

    /** The node's answer. */
    public ManagementFailure failure() {
        return failure;
    }

    /** Shorthand for {@code failure().reason()}. */
    public ManagementFailure.Reason reason() {
        return failure.reason();
    }
}
