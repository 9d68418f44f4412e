package io.etherware.core.component;

import io.etherware.core.message.Contents;
import io.etherware.core.message.Message;
import io.etherware.core.message.MessageId;
import io.etherware.core.message.Profile;
import io.etherware.core.message.QoS;
import io.etherware.core.time.NodeClock;
import java.util.concurrent.CompletableFuture;
import org.slf4j.Logger;

/**
 * What a component may do: send, reply, request, read the node's clock, know its own profile,
 * log. The kernel hands one context to each component in {@link Component#onStart}.
 *
 * <p>Thread-safety: every method may be called from any thread, including threads the component
 * starts itself. {@link #requestBlocking} is the exception: it must not be called on a dispatcher
 * thread, where it would wait for a reply that the same thread is supposed to deliver.
 *
 * <p>Sending never drops a message silently: if the receiver cannot be resolved, the component
 * receives an {@code undeliverable} notice (contents {@code Undeliverable}, a reply to the lost
 * message), or the request's future fails.
 */
public interface ComponentContext {

    /** This component's profile, which receivers see as the sender. */
    Profile self();

    /** The node's clock. */
    NodeClock clock();

    /** A logger named after this component. */
    Logger logger();

    /** Sends best-effort contents ({@link QoS#NONE}) to {@code to}. */
    default MessageId send(Profile to, Contents contents) {
        return send(to, contents, QoS.NONE);
    }

    /**
     * Sends {@code contents} to the component that {@code to} resolves to: an exact profile, or a
     * query (role plus some attributes) that matches exactly one component.
     *
     * @return the id of the message sent
     */
    MessageId send(Profile to, Contents contents, QoS qos);

    /**
     * Replies to {@code request}: a message to its sender, carrying the request's id as
     * correlation id and the request's QoS.
     *
     * @throws IllegalArgumentException if the request has no sender to reply to
     */
    MessageId reply(Message request, Contents contents);

    /**
     * Sends a request with the node's default timeout and best-effort QoS.
     *
     * @see #request(Profile, Contents, QoS, long)
     */
    CompletableFuture<Message> request(Profile to, Contents contents);

    /**
     * Sends a request and returns the future reply. The future completes on this component's
     * own dispatcher, one message at a time like any message to it, so its continuations
     * ({@code thenAccept} and the like, not the {@code ...Async} variants) may touch the
     * component's state safely. It fails with {@link RequestFailedException} on timeout, when the
     * request is undeliverable, when the responder throws, or when the node closes.
     *
     * <p>Never wait for the future on a dispatcher thread ({@code join}, {@code get}): the reply
     * needs this component's turn, which the waiting handler holds.
     *
     * @param timeoutNs how long to wait for the reply; must be &gt; 0
     */
    CompletableFuture<Message> request(Profile to, Contents contents, QoS qos, long timeoutNs);

    /**
     * Sends a request and waits for the reply, for code outside dispatcher threads (a
     * component's own I/O thread, {@link Component#onStart} at node start).
     *
     * @throws IllegalStateException  when called on a dispatcher thread (it would deadlock)
     * @throws RequestFailedException when no reply comes, for the reasons of {@link #request}
     */
    Message requestBlocking(Profile to, Contents contents, QoS qos, long timeoutNs);
}
