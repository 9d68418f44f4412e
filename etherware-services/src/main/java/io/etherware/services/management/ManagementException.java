package io.etherware.services.management;

import java.util.Objects;

/**
 * A refused or failed management operation, as the {@link Management} client's futures report it:
 * carries the node's {@link ManagementFailure}.
 *
 * <p>Immutable; safe to share between threads.
 */
public final class ManagementException extends RuntimeException {

    /** The node's answer. */
    private final ManagementFailure failure;

    /**
     * An exception for {@code failure}; its message names the operation, the target, the reason
     * and the node's error text.
     *
     * @param failure the node's answer
     * @throws NullPointerException if {@code failure} is null
     */
    public ManagementException(ManagementFailure failure) {
        super(failure.operation() + " of '" + failure.target() + "' failed (" + failure.reason() + "): "
                + failure.error());
        this.failure = Objects.requireNonNull(failure, "failure");
    }

    /**
     * The node's answer.
     *
     * @return the failure as the node sent it
     */
    public ManagementFailure failure() {
        return failure;
    }

    /**
     * Shorthand for {@code failure().reason()}.
     *
     * @return the kind of failure
     */
    public ManagementFailure.Reason reason() {
        return failure.reason();
    }
}
