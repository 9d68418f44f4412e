package io.etherware.core.component;

import io.etherware.core.message.MessageId;

/**
 * Why a request got no reply: the exception with which a request's future fails, and which the
 * blocking request throws.
 *
 * <p>Immutable; safe to share between threads.
 */
public final class RequestFailedException extends RuntimeException {

    /** What went wrong with the request. */
    public enum Reason {
        /** No reply within the timeout. */
        TIMEOUT,
        /** The request could not be delivered (unknown or ambiguous profile, stopped component). */
        UNDELIVERABLE,
        /** The responder threw while handling the request. */
        RESPONDER_FAILED,
        /** The node closed before the reply came. */
        NODE_CLOSED,
        /** The waiting thread was interrupted (blocking requests only). */
        INTERRUPTED
    }

    private final Reason reason;
    private final MessageId requestId;

    public RequestFailedException(Reason reason, MessageId requestId, String message) {
        super(message);
        this.reason = reason;
        this.requestId = requestId;
    }

    public RequestFailedException(Reason reason, MessageId requestId, String message, Throwable cause) {
        super(message, cause);
        this.reason = reason;
        this.requestId = requestId;
    }

    public Reason reason() {
        return reason;
    }

    /** The id of the request that failed. */
    public MessageId requestId() {
        return requestId;
    }
}
