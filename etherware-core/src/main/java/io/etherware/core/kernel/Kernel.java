package io.etherware.core.kernel;

import io.etherware.core.component.Component;
import io.etherware.core.component.ComponentState;
import io.etherware.core.component.Shell;
import io.etherware.core.message.Message;
import io.etherware.core.message.MessageId;
import io.etherware.core.message.Profile;
import io.etherware.core.time.NodeClock;
import java.time.Duration;
import java.util.Objects;
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
     * Makes the kernel keep the messages for a local component instead of dispatching them, from
     * the component's next message boundary on. The future completes once the component is at
     * that boundary and will not run until {@link #release}. Holding a held component completes
     * at once (holds do not nest).
     *
     * @param profile the exact profile of a local component, or a query that matches only it
     * @return a future that completes at the boundary: at once on the calling thread if the
     *         component is idle, else on the dispatcher thread that ends its current handling
     * @throws ProfileResolutionException if the profile does not resolve
     * @throws IllegalArgumentException   if it resolves to a component of another node
     */
    CompletableFuture<Void> holdAsync(Profile profile);

    /**
     * {@link #holdAsync(Profile)} at a boundary where the component is also quiescent: it waits for
     * no outcome of a request of its own (Kramer and Magee's passive state). Until then the
     * component runs on as usual, so the outcomes of its requests in flight reach it here, and a
     * migration that holds it this way moves no request that could not follow it. A component
     * that still waits for an outcome after {@code settleWait} is held at its next boundary
     * anyway (each boundary then, or at the latest when {@code settleWait} ends).
     *
     * <p>The default implementation, for kernels that do not track requests, holds at the next
     * boundary.
     *
     * @param profile    the exact profile of a local component, or a query that matches only it
     * @param settleWait how long to wait for the outcomes of its requests; zero holds at the next
     *                   boundary
     * @return a future that completes when the component is held
     * @throws ProfileResolutionException if the profile does not resolve
     * @throws IllegalArgumentException   if it resolves to a component of another node, or
     *                                    {@code settleWait} is negative
     */
    default CompletableFuture<Void> holdAsync(Profile profile, Duration settleWait) {
        if (Objects.requireNonNull(settleWait, "settleWait").isNegative()) {
            throw new IllegalArgumentException("settleWait=" + settleWait + " must not be negative");
        }
        return holdAsync(profile);
    }

    /**
     * Ends a hold: the messages kept meanwhile are delivered, in order, exactly once. Does
     * nothing for a component that is not held.
     *
     * @param profile the exact profile of a local component, or a query that matches only it
     * @throws ProfileResolutionException if the profile does not resolve
     * @throws IllegalArgumentException   if it resolves to a component of another node
     */
    void release(Profile profile);

    /**
     * Replaces a local component's logic at a message boundary: snapshot of the old logic, a new
     * instance from {@code factory}, {@code restore(state)}, {@code onStart}, swap, then the old
     * logic's {@code onStop}. If {@code restore} or {@code onStart} throws, the old logic stays
     * and the future fails with that error. The factory is also used for later restarts.
     *
     * @param profile the exact profile of a local component, or a query that matches only it
     * @param factory makes the new logic now and for the component's later restarts
     * @return a future that completes once the new logic is in place, or fails with the error of
     *         {@code restore} or {@code onStart}, or with an {@link IllegalStateException} if the
     *         component was not running
     * @throws ProfileResolutionException if the profile does not resolve
     * @throws IllegalArgumentException   if it resolves to a component of another node
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
     *
     * @param profile         the exact profile of a local component, or a query matching only it
     * @param factory         makes the new logic now and for the component's later restarts
     * @param onFirstHandling receives the start time of the new logic's first handling, in
     *                        nanoseconds of the node's monotonic clock
     * @return a future of the pause's timings, failing as {@link #swapAsync(Profile, Supplier)}'s
     * @throws ProfileResolutionException if the profile does not resolve
     * @throws IllegalArgumentException   if it resolves to a component of another node
     */
    default CompletableFuture<SwapTimings> swapAsync(Profile profile, Supplier<? extends Component> factory,
                                                     LongConsumer onFirstHandling) {
        return swapAsync(profile, factory).thenApply(swapped -> SwapTimings.UNMEASURED);
    }

    /**
     * {@link #swapAsync(Profile, Supplier, LongConsumer)} at a boundary where the component is
     * quiescent: it waits for no outcome of a request of its own (Kramer and Magee's passive
     * state, as {@link #holdAsync(Profile, Duration)} waits for it), so that the outcome of a
     * request in flight reaches the callback of the logic that made it, not a replaced one. One
     * that still waits after {@code settleWait} is swapped at its next boundary anyway.
     *
     * <p>The default implementation swaps at once.
     *
     * @param profile         the exact profile of a local component, or a query matching only it
     * @param factory         makes the new logic now and for the component's later restarts
     * @param onFirstHandling receives the start time of the new logic's first handling
     * @param settleWait      how long to wait for the outcomes of its requests; zero swaps at the
     *                        next boundary
     * @return a future of the pause's timings, failing as {@link #swapAsync(Profile, Supplier)}'s
     * @throws ProfileResolutionException if the profile does not resolve
     * @throws IllegalArgumentException   if it resolves to a component of another node, or
     *                                    {@code settleWait} is negative
     */
    default CompletableFuture<SwapTimings> swapAsync(Profile profile, Supplier<? extends Component> factory,
                                                     LongConsumer onFirstHandling, Duration settleWait) {
        if (Objects.requireNonNull(settleWait, "settleWait").isNegative()) {
            throw new IllegalArgumentException("settleWait=" + settleWait + " must not be negative");
        }
        return swapAsync(profile, factory, onFirstHandling);
    }

    /**
     * The state of a local component at its next message boundary ({@link Component#snapshot()},
     * possibly null). On a held component it is the state that a migration ships.
     *
     * @param profile the exact profile of a local component, or a query that matches only it
     * @return a future of the state (null for a stateless component), failing with what
     *         {@code snapshot()} threw
     * @throws ProfileResolutionException if the profile does not resolve
     * @throws IllegalArgumentException   if it resolves to a component of another node
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
     * @param route   the way to the node that takes the component over
     * @return a future that completes once the profile points at {@code route}
     * @throws ProfileResolutionException if the profile does not resolve
     * @throws IllegalArgumentException   if it is a query, or belongs to a component of another
     *                                    node
     */
    CompletableFuture<Void> relocateAsync(Profile profile, RemoteRoute route);

    /**
     * Adds a component that arrives by migration, <em>held</em>: registered under its
     * {@code profile} (displacing the route to its source) and under {@code arrival}, a profile of
     * its own to which the source forwards the messages it held and those that reach it until it
     * asks for the admission (then it sends to {@code profile}). Neither is announced as a second
     * component: {@code arrival} is known to the source only. Until {@link #admit} it handles nothing and keeps every message; the messages not sent to
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
     * @param profile         the component's exact profile, as on its source node
     * @param arrival         a profile of its own, to which the source forwards messages
     * @param factory         makes the instance, the first one already holding the migrated state,
     *                        and new ones for later restarts
     * @param onFirstHandling receives the start time of the first handled message, in
     *                        nanoseconds of the node's monotonic clock
     * @return the component's shell; if its {@code onStart} threw it is FAILED (remove it)
     * @throws IllegalArgumentException      if either profile is registered to a local component
     * @throws IllegalStateException         if the node does not run
     * @throws UnsupportedOperationException if this kernel cannot host migrated components
     */
    default Shell addHeld(Profile profile, Profile arrival, Supplier<? extends Component> factory,
                          LongConsumer onFirstHandling) {
        throw new UnsupportedOperationException(getClass().getName() + " cannot host migrated components");
    }

    /**
     * Completes an arrival ({@link #addHeld}) once {@code forwardedCount} messages to
     * {@code arrival} have come (at once if they have; 0 for at once): the component is released,
     * the messages kept so far are handled, the forwarded ones first, in order. The source says
     * how many it forwarded, because its request to admit may overtake some of them on the way;
     * it sends nothing more to {@code arrival}, so the admission unregisters it.
     *
     * @param arrival        the arrival profile given to {@link #addHeld}
     * @param forwardedCount how many messages the source forwarded to {@code arrival}; &gt;= 0
     * @throws IllegalArgumentException      if no migrated component arrived as {@code arrival}
     * @throws UnsupportedOperationException if this kernel cannot host migrated components (the
     *                                       default implementation)
     */
    default void admit(Profile arrival, long forwardedCount) {
        throw new UnsupportedOperationException(getClass().getName() + " cannot host migrated components");
    }

    /**
     * Removes a local component (by its profile, or the arrival profile of a migrated one):
     * unregistered at once, stopped at its next message boundary; the messages that waited for it
     * (also those kept by a hold) are resolved anew. The default implementation throws
     * {@link UnsupportedOperationException}.
     *
     * @param profile the exact profile of a local component, or the arrival profile of a
     *                migrated one
     * @return a future that completes once the component has stopped (at once if it never started)
     * @throws IllegalArgumentException      if no local component has that profile
     * @throws UnsupportedOperationException if this kernel cannot remove components
     */
    default CompletableFuture<Void> removeAsync(Profile profile) {
        throw new UnsupportedOperationException(getClass().getName() + " cannot remove components");
    }

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
