package io.etherware.core.kernel;

import io.etherware.core.component.Component;
import io.etherware.core.component.ComponentState;
import io.etherware.core.component.Shell;
import io.etherware.core.message.Profile;
import io.etherware.core.time.NodeClock;
import java.time.Duration;
import java.util.concurrent.CompletableFuture;
import java.util.function.LongConsumer;
import java.util.function.Supplier;

/**
 * The side of a node that hosts components, beyond delivering their messages ({@link Kernel}):
 * what runtime upgrade and migration need (paper Section VI-C). Hold and release a component at a
 * message boundary, swap its logic, take its state, relocate it behind a route to another node,
 * host one that arrives by migration, and remove one. {@link EtherwareNode} is one; a transport
 * needs only the {@link Kernel}.
 *
 * <p>Thread-safety: every method may be called from any thread. Methods returning a future do not
 * block; their futures may complete on a dispatcher thread.
 */
public interface ComponentHost extends Kernel {

    /**
     * Makes the kernel keep the messages for a local component instead of dispatching them, from
     * the component's next message boundary on. The future completes once the component is at
     * that boundary and will not run until {@link #release}. Holding a held component completes
     * at once (holds do not nest).
     *
     * @param profile the exact profile of a local component, or a query that matches only it
     * @return a future that completes at the boundary: at once on the calling thread if the
     *         component is idle, else on the dispatcher thread that ends its current handling;
     *         failed with an {@link IllegalStateException} if the component is still arriving by
     *         migration ({@link #addHeld}, not yet {@link #admit admitted}), or was removed before
     *         the boundary came
     * @throws ProfileResolutionException if the profile does not resolve
     * @throws IllegalArgumentException   if it resolves to a component of another node
     */
    CompletableFuture<Void> holdAsync(Profile profile);

    /**
     * {@link #holdAsync(Profile)} at a boundary where the component is also quiescent: it waits for
     * no outcome of a request of its own (Kramer and Magee's passive state), and no message from
     * another component is queued for it (one it sent itself does not count). Until then the
     * component runs on as usual, so the outcomes of its requests in flight and the messages
     * already waiting for it are handled here: a migration that holds it this way moves no
     * request that could not follow it, and carries no message queued before the hold across the
     * network behind the state, where it could arrive past its deadline (a control loop's Tick
     * queued at the hold would be a lost cycle). A component that is still not quiescent after
     * {@code settleWait} (it always has a request in flight, or messages keep coming faster than
     * it handles them) is held at its next boundary anyway (each boundary then, or at the latest
     * when {@code settleWait} ends).
     *
     * @param profile    the exact profile of a local component, or a query that matches only it
     * @param settleWait how long to wait for the component to be quiescent; zero holds at the
     *                   next boundary
     * @return a future that completes when the component is held; failed as
     *         {@link #holdAsync(Profile)}'s is
     * @throws ProfileResolutionException if the profile does not resolve
     * @throws IllegalArgumentException   if it resolves to a component of another node, or
     *                                    {@code settleWait} is negative
     */
    CompletableFuture<Void> holdAsync(Profile profile, Duration settleWait);

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
     * @param profile         the exact profile of a local component, or a query matching only it
     * @param factory         makes the new logic now and for the component's later restarts
     * @param onFirstHandling receives the start time of the new logic's first handling, in
     *                        nanoseconds of the node's monotonic clock
     * @return a future of the pause's timings, failing as {@link #swapAsync(Profile, Supplier)}'s
     * @throws ProfileResolutionException if the profile does not resolve
     * @throws IllegalArgumentException   if it resolves to a component of another node
     */
    CompletableFuture<SwapTimings> swapAsync(Profile profile, Supplier<? extends Component> factory,
                                             LongConsumer onFirstHandling);

    /**
     * {@link #swapAsync(Profile, Supplier, LongConsumer)} at a boundary where the component is
     * quiescent: it waits for no outcome of a request of its own (Kramer and Magee's passive
     * state, as {@link #holdAsync(Profile, Duration)} waits for it), so that the outcome of a
     * request in flight reaches the callback of the logic that made it, not a replaced one. One
     * that still waits after {@code settleWait} is swapped at its next boundary anyway.
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
    CompletableFuture<SwapTimings> swapAsync(Profile profile, Supplier<? extends Component> factory,
                                             LongConsumer onFirstHandling, Duration settleWait);

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
     * @throws IllegalStateException      if the component is still arriving by migration (not yet
     *                                    admitted): the messages its source forwards would come in
     *                                    after it left
     */
    CompletableFuture<Void> relocateAsync(Profile profile, RemoteRoute route);

    /**
     * Brings back, from {@code state}, a component this node relocated ({@link #relocateAsync})
     * whose new node holds no copy that could run (it died before taking the component over, or
     * gave it up): a new instance from the component's factory (the one its last upgrade
     * installed), restored to {@code state}, registered under its profile again (displacing the
     * relocation's route) and started. Once per relocation. The caller must know the other node's
     * copy cannot run, or two instances would. Messages that went along the route meanwhile are not
     * brought back.
     *
     * @param relocated the shell of the relocated component, as it was before the relocation
     * @param state     the state to resume from, as {@link #snapshotAsync} took it before the move;
     *                  null for a component without state (nothing is restored)
     * @return the new shell; if its {@code onStart} threw it is FAILED
     * @throws IllegalArgumentException if {@code relocated} is not a component this node relocated
     * @throws IllegalStateException    if its relocation has not pointed its profile at the route,
     *                                  it was reinstated already, or the node does not run
     * @throws Exception                what the new instance's {@code restore} threw; nothing was
     *                                  registered then
     */
    Shell reinstate(Shell relocated, ComponentState state) throws Exception;

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
     * @param profile         the component's exact profile, as on its source node
     * @param arrival         a profile of its own, to which the source forwards messages
     * @param factory         makes the instance, the first one already holding the migrated state,
     *                        and new ones for later restarts
     * @param onFirstHandling receives the start time of the first handled message, in
     *                        nanoseconds of the node's monotonic clock
     * @return the component's shell; if its {@code onStart} threw it is FAILED (remove it)
     * @throws IllegalArgumentException      if either profile is registered to a local component
     * @throws IllegalStateException         if the node does not run
     */
    Shell addHeld(Profile profile, Profile arrival, Supplier<? extends Component> factory,
                  LongConsumer onFirstHandling);

    /**
     * Completes an arrival ({@link #addHeld}) once {@code forwardedCount} messages to
     * {@code arrival} have come (at once if they have; 0 for at once): the component is released,
     * the messages kept so far are handled, the forwarded ones first, in order. The source says
     * how many it forwarded, because its request to admit may overtake some of them on the way;
     * it sends nothing more to {@code arrival}, so once that many are in, {@code arrival} is
     * unregistered. A later call with a lower count (a forwarded message was refused on the way)
     * admits at once, but {@code arrival} stays registered until the first call's count is in,
     * for a message that was only late.
     *
     * @param arrival        the arrival profile given to {@link #addHeld}
     * @param forwardedCount how many messages the source forwarded to {@code arrival}; &gt;= 0
     * @throws IllegalArgumentException      if no migrated component arrived as {@code arrival}
     */
    void admit(Profile arrival, long forwardedCount);

    /**
     * Removes a local component (by its profile, or the arrival profile of a migrated one):
     * unregistered at once, stopped at its next message boundary; the messages that waited for it
     * (also those kept by a hold) are resolved anew.
     *
     * @param profile the exact profile of a local component, or the arrival profile of a
     *                migrated one
     * @return a future that completes once the component has stopped (at once if it never started)
     * @throws IllegalArgumentException      if no local component has that profile
     */
    CompletableFuture<Void> removeAsync(Profile profile);
}
