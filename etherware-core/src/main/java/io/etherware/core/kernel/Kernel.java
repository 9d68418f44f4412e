package io.etherware.core.kernel;

import io.etherware.core.message.Message;
import io.etherware.core.message.MessageId;
import io.etherware.core.message.Profile;
import io.etherware.core.scheduler.Scheduler;
import io.etherware.core.time.NodeClock;
import java.util.concurrent.CompletableFuture;

/**
 * The message-delivery mechanism of a node (paper Section III-A, Fig. 2), as the node's services
 * see it: a transport injects incoming messages with {@link #send} and registers routes in the
 * {@link #registry()}. What upgrade and migration need besides (hold, swap, snapshot, relocate,
 * admit, remove) is on {@link ComponentHost}, the side of a node that hosts components.
 *
 * <p>Delivery: {@link #send} resolves the profile, wraps the message in a job and hands it to the
 * scheduler (or to a {@link RemoteRoute}). A component handles one message at a time on whatever
 * dispatcher the scheduler chose; a message for a busy component waits with the component, so a
 * message waits at most for the handling in progress on its component plus the more urgent
 * messages already waiting for it, and a dispatcher never blocks on another's work.
 *
 * <p>Thread-safety: every method may be called from any thread. Methods returning a future do not
 * block; their futures may complete on a dispatcher thread.
 */
public interface Kernel {

    /** {@return this node's id, unique in the system and the node part of its message ids} */
    String nodeId();

    /**
     * {@return the node's own profile, {@code etherware.node[id=<nodeId>]}} It is the sender of
     * requests made from outside any component, so replies find their way back across nodes.
     */
    Profile profile();

    /** {@return the node's clock, which time-stamps its messages and drives its dispatchers} */
    NodeClock clock();

    /** {@return the profile registry, where transports register their remote routes} */
    ProfileRegistry registry();

    /** {@return a new message id of this node, never returned before while it runs} Lock-free. */
    MessageId newMessageId();

    /**
     * Delivers {@code message} to the component or route its profile resolves to. Never drops a
     * message silently: if the profile does not resolve, the sender receives an
     * {@link Undeliverable} notice (a request's future fails), and a counter moves. A reply to a
     * pending request of this node completes that request instead.
     *
     * @param message the message; its profile may be an exact profile or a query
     * @throws IllegalStateException if the node was never started
     */
    void send(Message message);

    /**
     * Sends {@code request} and returns its reply. If the request has no sender, the node's
     * {@link #profile()} is used. The future completes on a kernel thread (use the
     * {@code ...Async} continuations for long work) and fails with
     * {@link io.etherware.core.component.RequestFailedException}.
     *
     * @param request   the request, with a new id of this node
     * @param timeoutNs how long to wait for the reply, in nanoseconds; &gt; 0
     * @return the future reply
     * @throws IllegalArgumentException if {@code timeoutNs} is not positive, or a request with the
     *                                  same id is still waiting
     * @throws IllegalStateException    if the node was never started or is closed
     */
    CompletableFuture<Message> request(Message request, long timeoutNs);

    /**
     * {@return the node's scheduler} A transport reads its thread scheduling rule to run its own
     * threads at the right priorities.
     */
    Scheduler scheduler();

    /**
     * {@return a future that completes when the node has closed, whoever closed it} A transport
     * closes itself then.
     */
    CompletableFuture<Void> closedFuture();

    /** {@return the node's counters now, each exact but not read atomically together} */
    NodeStats stats();

    /**
     * The node's registry of contents types ({@link NodeConfig#contentsTypes()}): what the codecs
     * that carry this node's messages (the network's, state snapshots) can encode and decode.
     * Services register their own types here when they are installed on the node.
     *
     * @return the node's registry; thread-safe
     */
    io.etherware.core.message.ContentsTypes contentsTypes();

    /**
     * Bytes of messages that arrived through node {@code viaNodeId} (their
     * {@link io.etherware.core.message.Origin#wireBytes()}) and wait in this node's queues, not
     * yet handled or passed on: what a peer has made this node hold, so the network layer can
     * stop reading from a peer that floods it. The default implementation does not count.
     *
     * @param viaNodeId the peer whose connection delivered them, their
     *                  {@link io.etherware.core.message.Origin#viaNodeId()}
     * @return the bytes, &gt;= 0; 0 if none wait or the kernel does not count
     */
    default long queuedBytesFrom(String viaNodeId) {
        return 0;
    }
}
