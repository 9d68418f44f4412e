package io.etherware.core.kernel;

import io.etherware.core.message.Contents;
import java.util.Objects;

/**
 * The kernel's notice that a responder threw while handling a request, sent as the reply to it so
 * the requester's future fails naming the cause. Registered as {@code request-failed}.
 *
 * @param requestId the request's id, {@code node#sequence}
 * @param responder the responder's profile, in text form
 * @param reason    the exception the responder threw: its class and message
 */
public record RequestFailed(String requestId, String responder, String reason) implements Contents {
    /**
     * Checks that every component is given.
     *
     * @throws NullPointerException if a component is null
     */
    public RequestFailed {
        Objects.requireNonNull(requestId, "requestId");
        Objects.requireNonNull(responder, "responder");
        Objects.requireNonNull(reason, "reason");
    }
}
