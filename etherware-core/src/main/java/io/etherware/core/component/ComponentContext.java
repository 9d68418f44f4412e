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

    /** {@return this component's profile, which receivers see as the sender} */
    Profile self();

    /** {@return the node's clock, for time stamps and for measuring on the monotonic clock} */
    NodeClock clock();

    /** {@return a logger named after this component ({@code etherware.component.<profile>})} */
    Logger logger();

    /**
     * Sends best-effort contents ({@link QoS#NONE}) to {@code to}.
     *
     * @param to       the receiver: an exact profile or a query that matches exactly one component
     * @param contents the payload, a registered record
     * @return the id of the message sent
     * @see #send(Profile, Contents, QoS)
     */
    default MessageId send(Profile to, Contents contents) {
        return send(to, contents, QoS.NONE);
    }

    /**
     * Sends {@code contents} to the component that {@code to} resolves to: an exact profile, or a
     * query (role plus some attributes) that matches exactly one component.
     *
     * @param to       the receiver: an exact profile or a query that matches exactly one component
     * @param contents the payload, a registered record
     * @param qos      the delivery requirements; {@link QoS#NONE} for best effort
     * @return the id of the message sent
     */
    MessageId send(Profile to, Contents contents, QoS qos);

    /**
     * Replies to {@code request}: a message to its sender, carrying the request's id as
     * correlation id and the request's QoS.
     *
     * @param request  the message to answer
     * @param contents the reply's payload, a registered record
     * @return the id of the reply
     * @throws IllegalArgumentException if the request has no sender to reply to
     */
    MessageId reply(Message request, Contents contents);

    /**
     * Sends a request with the node's default timeout and best-effort QoS.
     *
     * @param to       the responder: an exact profile or a query that matches exactly one component
     * @param contents the request's payload, a registered record
     * @return the future reply, completed on this component's dispatcher
     * @throws IllegalStateException if the node is closed
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
     * @param to        the responder: an exact profile or a query matching exactly one component
     * @param contents  the request's payload, a registered record
     * @param qos       the delivery requirements of the request (and of a reply made with
     *                  {@link #reply})
     * @param timeoutNs how long to wait for the reply, in nanoseconds; must be &gt; 0
     * @return the future reply, completed on this component's dispatcher
     * @throws IllegalArgumentException if {@code timeoutNs} is not positive
     * @throws IllegalStateException    if the node is closed
     */
    CompletableFuture<Message> request(Profile to, Contents contents, QoS qos, long timeoutNs);

    /**
     * Sends a request and waits for the reply, for code outside dispatcher threads (a
     * component's own I/O thread, {@link Component#onStart} at node start).
     *
     * @param to        the responder: an exact profile or a query matching exactly one component
     * @param contents  the request's payload, a registered record
     * @param qos       the delivery requirements of the request
     * @param timeoutNs how long to wait for the reply, in nanoseconds; must be &gt; 0
     * @return the reply
     * @throws IllegalArgumentException if {@code timeoutNs} is not positive
     * @throws IllegalStateException  when called on a dispatcher thread (it would deadlock), or
     *                                when the node is closed
     * @throws RequestFailedException when no reply comes, for the reasons of {@link #request}
     */
    Message requestBlocking(Profile to, Contents contents, QoS qos, long timeoutNs);
}
