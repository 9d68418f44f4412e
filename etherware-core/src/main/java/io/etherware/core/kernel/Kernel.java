package io.etherware.core.kernel;

import io.etherware.core.component.Component;
import io.etherware.core.component.ComponentState;
import io.etherware.core.component.Shell;
import io.etherware.core.message.Message;
import io.etherware.core.message.MessageId;
import io.etherware.core.message.Profile;
import io.etherware.core.time.NodeClock;
import java.util.concurrent.CompletableFuture;
import java.util.function.LongConsumer;
import java.util.function.Supplier;

/**
 * The message-delivery and management mechanism of a node (paper Section III-A, Fig. 2), as the
 * node's services see it: a transport injects incoming messages with {@link #send} and registers
 * routes in the {@link #registry()}; upgrade and migration use the hold / release / swap hooks.
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

    /** This node's id. */
    String nodeId();

    /**
     * The node's own profile, {@code etherware.node[id=<nodeId>]}: the sender of requests made
     * from outside any component, so replies find their way back across nodes.
     */
    Profile profile();

    /** The node's clock. */
    NodeClock clock();

    /** The profile registry. */
    ProfileRegistry registry();

    /** A new message id of this node. */
    MessageId newMessageId();

    /**
     * Delivers {@code message} to the component or route its profile resolves to. Never drops a
     * message silently: if the profile does not resolve, the sender receives an
     * {@link Undeliverable} notice (a request's future fails), and a counter moves. A reply to a
     * pending request of this node completes that request instead.
     *
     * @throws IllegalStateException if the node was never started
     */
    void send(Message message);

    /**
     * Sends {@code request} and returns its reply. If the request has no sender, the node's
     * {@link #profile()} is used. The future completes on a kernel thread (use the
     * {@code ...Async} continuations for long work) and fails with
     * {@link io.etherware.core.component.RequestFailedException}.
     */
    CompletableFuture<Message> request(Message request, long timeoutNs);

    /**
     * Makes the kernel keep the messages for a local component instead of dispatching them, from
     * the component's next message boundary on. The future completes once the component is at
     * that boundary and will not run until {@link #release}. Holding a held component completes
     * at once (holds do not nest).
     *
     * @throws ProfileResolutionException if no local component has exactly this profile
     */
    CompletableFuture<Void> holdAsync(Profile profile);

    /**
     * Ends a hold: the messages kept meanwhile are delivered, in order, exactly once. Does
     * nothing for a component that is not held.
     */
    void release(Profile profile);

    /**
     * Replaces a local component's logic at a message boundary: snapshot of the old logic, a new
     * instance from {@code factory}, {@code restore(state)}, {@code onStart}, swap, then the old
     * logic's {@code onStop}. If {@code restore} or {@code onStart} throws, the old logic stays
     * and the future fails with that error. The factory is also used for later restarts.
     */
    CompletableFuture<Void> swapAsync(Profile profile, Supplier<? extends Component> factory);

    /**
     * {@link #swapAsync(Profile, Supplier)}, timed, for measuring the swap gap (the last message
     * handled by the old logic to the first handled by the new one). The future completes with the
     * {@link SwapTimings} of the pause, on the thread that ran the swap while it still holds the
     * component: continue with the {@code ...Async} forms. Then {@code onFirstHandling} receives the
     * time ({@link NodeClock#nanoTime()}) at which the new logic's first message began; it is
     * called once, on that message's dispatcher thread after the handling, so it must be quick and
     * must not block. It is never called if the swap rolls back, or if the new logic is replaced or
     * stops before it handles a message.
     *
     * <p>The default implementation, for kernels that do not time swaps, swaps and reports
     * {@link SwapTimings#UNMEASURED}; it never calls {@code onFirstHandling}.
     */
    default CompletableFuture<SwapTimings> swapAsync(Profile profile, Supplier<? extends Component> factory,
                                                     LongConsumer onFirstHandling) {
        return swapAsync(profile, factory).thenApply(swapped -> SwapTimings.UNMEASURED);
    }

    /**
     * The state of a local component at its next message boundary ({@link Component#snapshot()},
     * possibly null). On a held component it is the state that a migration ships.
     */
    CompletableFuture<ComponentState> snapshotAsync(Profile profile);

    /**
     * Moves a local component's profile to another node, at the component's next message
     * boundary: stops the component and forwards the messages kept by a {@link #holdAsync hold}
     * through {@code route}, in order; messages still queued at dispatchers for it (or sent to it
     * meanwhile) follow through the route as they are taken; once none is left, the profile is
     * pointed at {@code route} and the future completes. No message sent through this node
     * overtakes an earlier one of the same sender and urgency.
     *
     * @param profile the exact profile of a local component
     */
    CompletableFuture<Void> relocateAsync(Profile profile, RemoteRoute route);

    /**
     * Adds a component that arrives by migration, <em>held</em>: registered under its
     * {@code profile} (displacing the route to its source) and under {@code arrival}, a profile of
     * its own to which the source forwards the messages it held and those that still reach it.
     * Until {@link #admit} it handles nothing and keeps every message; the messages not sent to
     * {@code arrival} are <em>penned</em>: kept behind the forwarded ones of the same urgency
     * (also after the admission, until the last penned one has run), because anything that came
     * through the source was sent before what comes here directly. The component is started now
     * (its {@link io.etherware.core.component.ComponentContext#self()} is {@code profile}); the
     * instance the factory returns first should already hold the migrated state. Its first handled
     * message is reported to {@code onFirstHandling} ({@link NodeClock#nanoTime()} of its start, on
     * that message's dispatcher after the handling; must be quick).
     *
     * <p>The default implementation, for kernels that cannot host migrated components, throws
     * {@link UnsupportedOperationException}.
     *
     * @return the component's shell; if its {@code onStart} threw it is FAILED (remove it)
     * @throws IllegalArgumentException if either profile is registered to a local component
     * @throws IllegalStateException    if the node does not run
     */
    default Shell addHeld(Profile profile, Profile arrival, Supplier<? extends Component> factory,
                          LongConsumer onFirstHandling) {
        throw new UnsupportedOperationException(getClass().getName() + " cannot host migrated components");
    }

    /**
     * Completes an arrival ({@link #addHeld}) once {@code forwardedCount} messages to
     * {@code arrival} have come (at once if they have; 0 for at once): the component is released,
     * the messages kept so far are handled, the forwarded ones first, in order. The source says
     * how many it forwarded, because its request to admit may overtake some of them on the way.
     * {@code arrival} stays registered for messages still on their way through the source.
     *
     * @throws IllegalArgumentException if no migrated component arrived as {@code arrival}
     */
    default void admit(Profile arrival, long forwardedCount) {
        throw new UnsupportedOperationException(getClass().getName() + " cannot host migrated components");
    }

    /**
     * Removes a local component (by its profile, or the arrival profile of a migrated one):
     * unregistered at once, stopped at its next message boundary; the messages that waited for it
     * (also those kept by a hold) are resolved anew. The default implementation throws
     * {@link UnsupportedOperationException}.
     */
    default CompletableFuture<Void> removeAsync(Profile profile) {
        throw new UnsupportedOperationException(getClass().getName() + " cannot remove components");
    }

    /** The node's counters now. */
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
     */
    default long queuedBytesFrom(String viaNodeId) {
        return 0;
    }
}
