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

    /** What went wrong. */
    private final Reason reason;
    /** The request that failed. */
    private final MessageId requestId;

    /**
     * A failure without an underlying exception.
     *
     * @param reason    what went wrong
     * @param requestId the id of the request that failed
     * @param message   the text for logs, naming the request and the cause
     */
    public RequestFailedException(Reason reason, MessageId requestId, String message) {
        super(message);
        this.reason = reason;
        this.requestId = requestId;
    }

    /**
     * A failure caused by another exception.
     *
     * @param reason    what went wrong
     * @param requestId the id of the request that failed
     * @param message   the text for logs, naming the request and the cause
     * @param cause     the underlying exception, e.g. the interruption or an earlier failure
     */
    public RequestFailedException(Reason reason, MessageId requestId, String message, Throwable cause) {
        super(message, cause);
        this.reason = reason;
        this.requestId = requestId;
    }

    /** {@return what went wrong, for code that treats a timeout unlike a refusal} */
    public Reason reason() {
        return reason;
    }

    /** {@return the id of the request that failed} */
    public MessageId requestId() {
        return requestId;
    }
}
