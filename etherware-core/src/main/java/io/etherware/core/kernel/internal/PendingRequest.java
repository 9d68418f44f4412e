package io.etherware.core.kernel.internal;

import io.etherware.core.message.Message;
import io.etherware.core.message.MessageId;
import java.util.concurrent.CompletableFuture;
import java.util.concurrent.ScheduledFuture;

/**
 * A request waiting for its reply. When the requester is a component, the outcome is handed to it
 * as a job of its own (this object is the job's target), so the future completes within the
 * component's exclusive turn; otherwise the future completes on the thread that has the outcome.
 *
 * <p>Thread-safety: whoever removes the entry from the {@link RequestTable} settles it, exactly
 * once; the outcome fields are written before the job is published to a scheduler queue.
 */
final class PendingRequest {

    final MessageId id;
    final Message request;
    /** The requesting component, or null for a request from outside or a blocking request. */
    final LocalShell requester;
    final CompletableFuture<Message> future = new CompletableFuture<>();
    volatile ScheduledFuture<?> timeout;

    private Message reply;
    private RuntimeException failure;

    PendingRequest(Message request, LocalShell requester) {
        this.id = request.messageId();
        this.request = request;
        this.requester = requester;
    }

    void succeedWith(Message message) {
        reply = message;
    }

    void failWith(RuntimeException error) {
        failure = error;
    }

    /** The message the outcome job carries: the reply, or the request for a failure. */
    Message outcomeMessage() {
        return reply != null ? reply : request;
    }

    /** Completes the future with the recorded outcome (once), then counts it settled for its requester. */
    void settle() {
        try {
            if (failure != null) {
                future.completeExceptionally(failure);
            } else {
                future.complete(reply);
            }
        } finally {
            if (requester != null) {
                requester.requestSettled();
            }
        }
    }
}
