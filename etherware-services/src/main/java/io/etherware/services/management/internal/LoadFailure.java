package io.etherware.services.management.internal;

import io.etherware.services.management.ManagementFailure;

/**
 * Why an implementation could not be loaded or constructed; becomes a {@link ManagementFailure}.
 *
 * <p>Immutable; safe to share between threads.
 */
public final class LoadFailure extends Exception {

    private final ManagementFailure.Reason reason;

    public LoadFailure(ManagementFailure.Reason reason, String message) {
        super(message);
        this.reason = reason;
    }

    public LoadFailure(ManagementFailure.Reason reason, String message, Throwable cause) {
        super(message, cause);
        this.reason = reason;
    }

    public ManagementFailure.Reason reason() {
        return reason;
    }
}
