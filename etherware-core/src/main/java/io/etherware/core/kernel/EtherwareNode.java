package io.etherware.core.kernel;

import io.etherware.core.component.Component;
import io.etherware.core.component.ComponentState;
import io.etherware.core.component.Shell;
import io.etherware.core.kernel.internal.DispatcherMark;
import io.etherware.core.kernel.internal.KernelCore;
import io.etherware.core.message.Contents;
import io.etherware.core.message.ContentsTypes;
import io.etherware.core.message.Message;
import io.etherware.core.message.MessageId;
import io.etherware.core.message.Profile;
import io.etherware.core.message.QoS;
import io.etherware.core.scheduler.Scheduler;
import io.etherware.core.time.NodeClock;
import java.time.Duration;
import java.util.List;
import java.util.concurrent.CompletableFuture;
import java.util.concurrent.ExecutionException;
import java.util.concurrent.TimeUnit;
import java.util.concurrent.TimeoutException;
import java.util.function.LongConsumer;
import java.util.function.Supplier;
import org.slf4j.Logger;
import org.slf4j.LoggerFactory;

/**
 * An Etherware node: a kernel, its scheduler and its components (paper Fig. 2).
 *
 * <pre>{@code
 * try (EtherwareNode node = EtherwareNode.builder().nodeId("plant-1").build()) {
 *     node.add(Profile.of("echo"), () -> (message, context) -> context.reply(message, message.contents()));
 *     node.start();
 *     Message reply = node.requestBlocking(Profile.of("echo"), new Text("hi"));
 * }
 * }</pre>
 *
 * <p>Lifecycle: build, add components, {@link #start()} (scheduler, then components in
 * registration order), add or remove components while running, {@link #close()} (drain for the
 * configured time, count the rest as discarded, stop components in reverse order). Supervision:
 * a component that throws is restarted by its {@link SupervisionPolicy}; past its intensity the
 * node applies its {@link Escalation}.
 *
 * <p>Thread-safety: every method may be called from any thread. The blocking methods
 * ({@link #requestBlocking}, {@link #hold}, {@link #swap}, {@link #remove}, {@link #close})
 * refuse dispatcher threads, where they could wait for themselves; use the asynchronous forms
 * there.
 */
public final class EtherwareNode implements ComponentHost, AutoCloseable {

    private static final Logger log = LoggerFactory.getLogger(Kernel.class);

    private final KernelCore core;

    private EtherwareNode(NodeConfig config) {
        this.core = new KernelCore(config);
    }

    /** {@return a builder with the defaults of {@link NodeConfig.Builder}} */
    public static Builder builder() {
        return new Builder();
    }

    /**
     * A node with the given configuration, not started. Calls the scheduler factory once.
     *
     * @param config the node's configuration, validated when it was built
     * @return the node
     */
    public static EtherwareNode create(NodeConfig config) {
        return new EtherwareNode(config);
    }

    /**
     * Registers the kernel's notices ({@code undeliverable}, {@code request-failed}) and markers
     * ({@code order-marker}, see {@link OrderMarker}) in a contents registry. A node does this for its own registry ({@link #contentsTypes()}); call it
     * for a codec built apart from a node that must read a node's notices.
     *
     * @param types a registry for a codec that must read or write the notices
     * @throws IllegalArgumentException if either name is already registered for another type
     */
    public static void registerContents(ContentsTypes types) {
        KernelCore.registerContents(types);
    }

    /** {@return the configuration the node was built with} */
    public NodeConfig config() {
        return core.config();
    }

    // ---------------------------------------------------------------- lifecycle

    /**
     * Starts the scheduler, then the components in registration order, on the calling thread. A
     * component whose {@code onStart} throws is FAILED; the others start regardless.
     *
     * @return this node
     * @throws IllegalStateException if the node was started or closed before
     */
    public EtherwareNode start() {
        core.start();
        return this;
    }

    /**
     * Adds a component with the node's default supervision policy; starts it now if the node
     * runs. {@code factory} makes the first instance now and new ones for restarts.
     *
     * @param profile the component's exact profile; a remote route registered for it is displaced
     * @param factory makes the component's logic: the first instance now (what it throws
     *                propagates), new ones for restarts
     * @return the component's shell
     * @throws IllegalArgumentException if a local component already has the profile
     * @throws IllegalStateException    if the node is closing or closed
     */
    public Shell add(Profile profile, Supplier<? extends Component> factory) {
        return core.add(profile, factory, core.config().supervision());
    }

    /**
     * Adds a component with its own supervision policy; starts it now if the node runs.
     *
     * @param profile     the component's exact profile; a remote route registered for it is
     *                    displaced
     * @param factory     makes the component's logic: the first instance now (what it throws
     *                    propagates), new ones for restarts
     * @param supervision the component's restart policy
     * @return the component's shell
     * @throws IllegalArgumentException if a local component already has the profile
     * @throws IllegalStateException    if the node is closing or closed
     */
    public Shell add(Profile profile, Supplier<? extends Component> factory, SupervisionPolicy supervision) {
        return core.add(profile, factory, supervision);
    }

    /**
     * Removes a component: unregistered at once, stopped at its next message boundary; the
     * messages that waited for it are resolved anew (to wherever the profile lives now, or back
     * to their senders as undeliverable).
     */
    @Override
    public CompletableFuture<Void> removeAsync(Profile profile) {
        return core.remove(profile);
    }

    /**
     * {@link #removeAsync} and wait until the component has stopped.
     *
     * @param profile the exact profile of a local component, or the arrival profile of a
     *                migrated one
     * @throws IllegalArgumentException if no local component has that profile
     * @throws IllegalStateException    on a dispatcher thread, if interrupted, or if the component
     *                                  does not reach a message boundary in time
     */
    public void remove(Profile profile) {
        await(removeAsync(profile), "remove", profile);
    }

    /**
     * The shell of a local component.
     *
     * @param profile the exact profile of a local component, or a query that matches only it
     * @return its shell
     * @throws ProfileResolutionException if the profile does not resolve
     * @throws IllegalArgumentException   if it resolves to a component of another node
     */
    public Shell shell(Profile profile) {
        return core.shell(profile);
    }

    /**
     * Lets {@code tap} see every message this node is asked to deliver from now on (see
     * {@link MessageTap} for the threading contract), until the returned registration is closed.
     *
     * @param tap what to tell
     * @return closes the tap: it sees no message sent after {@code close} returns
     */
    public MessageTap.Registration tap(MessageTap tap) {
        core.addTap(tap);
        return () -> core.removeTap(tap);
    }

    /** {@return the registered local components, in registration order: a copy taken now} */
    public List<Shell> shells() {
        return core.shells();
    }

    /** {@return whether the node has started and has not begun to close} */
    public boolean isRunning() {
        return core.isRunning();
    }

    /** {@return whether the node has finished closing} */
    public boolean isClosed() {
        return core.isClosed();
    }

    /**
     * Closes the node on a new thread, so a component may call it. Does nothing more if the node
     * is already closing.
     *
     * @return a future that completes when the node is closed
     */
    public CompletableFuture<Void> closeAsync() {
        return core.closeAsync();
    }

    /**
     * {@return a future that completes when the node has closed, whoever closed it (escalation
     * may)}
     */
    @Override
    public CompletableFuture<Void> closedFuture() {
        return core.closedFuture();
    }

    /**
     * Lets queued messages be delivered for at most the drain timeout, counts the rest as
     * discarded, stops the components in reverse registration order and fails waiting requests.
     * Idempotent.
     *
     * @throws IllegalStateException on a dispatcher thread (use {@link #closeAsync()})
     */
    @Override
    public void close() {
        core.close();
    }

    // ---------------------------------------------------------------- messaging from outside

    /**
     * Sends best-effort contents from outside any component (no sender).
     *
     * @param to       the receiver: an exact profile or a query matching exactly one component
     * @param contents the payload, a registered record
     * @return the id of the message sent
     * @throws IllegalStateException if the node was never started
     */
    public MessageId send(Profile to, Contents contents) {
        return send(to, contents, QoS.NONE);
    }

    /**
     * Sends contents from outside any component (no sender: nobody gets a notice if it is lost).
     *
     * @param to       the receiver: an exact profile or a query matching exactly one component
     * @param contents the payload, a registered record
     * @param qos      the delivery requirements; {@link QoS#NONE} for best effort
     * @return the id of the message sent
     * @throws IllegalStateException if the node was never started
     */
    public MessageId send(Profile to, Contents contents, QoS qos) {
        MessageId id = core.newMessageId();
        core.send(new Message(to, null, core.clock().epochNanos(), qos, contents, id, null));
        return id;
    }

    /**
     * A best-effort request from outside with the default timeout; see {@link Kernel#request}.
     *
     * @param to       the responder: an exact profile or a query matching exactly one component
     * @param contents the request's payload, a registered record
     * @return the future reply; it fails with
     *         {@link io.etherware.core.component.RequestFailedException}
     * @throws IllegalStateException if the node was never started or is closed
     */
    public CompletableFuture<Message> request(Profile to, Contents contents) {
        return request(to, contents, QoS.NONE, core.config().defaultRequestTimeoutNs());
    }

    /**
     * A request from outside; the node's {@link #profile()} is its sender.
     *
     * @param to        the responder: an exact profile or a query matching exactly one component
     * @param contents  the request's payload, a registered record
     * @param qos       the delivery requirements of the request
     * @param timeoutNs how long to wait for the reply, in nanoseconds; &gt; 0
     * @return the future reply; it fails with
     *         {@link io.etherware.core.component.RequestFailedException}
     * @throws IllegalArgumentException if {@code timeoutNs} is not positive
     * @throws IllegalStateException    if the node was never started or is closed
     */
    public CompletableFuture<Message> request(Profile to, Contents contents, QoS qos, long timeoutNs) {
        return core.request(outsideMessage(to, contents, qos), timeoutNs);
    }

    /**
     * A best-effort blocking request from outside with the default timeout.
     *
     * @param to       the responder: an exact profile or a query matching exactly one component
     * @param contents the request's payload, a registered record
     * @return the reply
     * @throws io.etherware.core.component.RequestFailedException if no reply comes
     * @throws IllegalStateException on a dispatcher thread, or if the node was never started or
     *                               is closed
     */
    public Message requestBlocking(Profile to, Contents contents) {
        return requestBlocking(to, contents, QoS.NONE, core.config().defaultRequestTimeoutNs());
    }

    /**
     * A blocking request from outside.
     *
     * @param to        the responder: an exact profile or a query matching exactly one component
     * @param contents  the request's payload, a registered record
     * @param qos       the delivery requirements of the request
     * @param timeoutNs how long to wait for the reply, in nanoseconds; &gt; 0
     * @return the reply
     * @throws io.etherware.core.component.RequestFailedException if no reply comes
     * @throws IllegalArgumentException if {@code timeoutNs} is not positive
     * @throws IllegalStateException on a dispatcher thread, or if the node was never started or
     *                               is closed
     */
    public Message requestBlocking(Profile to, Contents contents, QoS qos, long timeoutNs) {
        return core.requestBlocking(outsideMessage(to, contents, qos), timeoutNs);
    }

    private Message outsideMessage(Profile to, Contents contents, QoS qos) {
        return new Message(to, core.profile(), core.clock().epochNanos(), qos, contents, core.newMessageId(), null);
    }

    // ---------------------------------------------------------------- management, blocking forms

    /**
     * {@link #holdAsync} and wait for the component's message boundary.
     *
     * @param profile the exact profile of a local component, or a query that matches only it
     * @throws ProfileResolutionException if the profile does not resolve
     * @throws IllegalArgumentException   if it resolves to a component of another node
     * @throws IllegalStateException      on a dispatcher thread, if interrupted, or if the
     *                                    component does not reach a message boundary in time
     */
    public void hold(Profile profile) {
        await(holdAsync(profile), "hold", profile);
    }

    /**
     * {@link #swapAsync} and wait.
     *
     * @param profile the exact profile of a local component, or a query that matches only it
     * @param factory makes the new logic now and for the component's later restarts
     * @throws ProfileResolutionException if the profile does not resolve
     * @throws IllegalArgumentException   if it resolves to a component of another node
     * @throws IllegalStateException      carrying the error if the swap was rolled back; also on a
     *                                    dispatcher thread, if interrupted, or if the component
     *                                    does not reach a message boundary in time
     */
    public void swap(Profile profile, Supplier<? extends Component> factory) {
        await(swapAsync(profile, factory), "swap", profile);
        log.info("node {}: component '{}' swapped to its new logic", core.nodeId(), profile);
    }

    private void await(CompletableFuture<Void> operation, String what, Profile profile) {
        DispatcherMark.requireNotDispatcher(what + "(" + profile + ")", "Use " + what + "Async(...).");
        try {
            operation.get(core.config().defaultRequestTimeoutNs() + TimeUnit.SECONDS.toNanos(10), TimeUnit.NANOSECONDS);
        } catch (InterruptedException e) {
            Thread.currentThread().interrupt();
            throw new IllegalStateException(what + " of '" + profile + "' interrupted", e);
        } catch (ExecutionException e) {
            throw new IllegalStateException(what + " of '" + profile + "' failed: " + e.getCause(), e.getCause());
        } catch (TimeoutException e) {
            throw new IllegalStateException(what + " of '" + profile + "' did not reach a message boundary in time;"
                    + " is the component stuck in a handler?", e);
        }
    }

    // ---------------------------------------------------------------- Kernel

    @Override
    public String nodeId() {
        return core.nodeId();
    }

    @Override
    public Profile profile() {
        return core.profile();
    }

    @Override
    public NodeClock clock() {
        return core.clock();
    }

    @Override
    public ProfileRegistry registry() {
        return core.registry();
    }

    @Override
    public MessageId newMessageId() {
        return core.newMessageId();
    }

    @Override
    public void send(Message message) {
        core.send(message);
    }

    @Override
    public CompletableFuture<Message> request(Message request, long timeoutNs) {
        return core.request(request, timeoutNs);
    }

    @Override
    public CompletableFuture<Void> holdAsync(Profile profile) {
        return core.holdAsync(profile);
    }

    @Override
    public CompletableFuture<Void> holdAsync(Profile profile, Duration settleWait) {
        return core.holdAsync(profile, settleWait);
    }

    @Override
    public void release(Profile profile) {
        core.release(profile);
    }

    @Override
    public CompletableFuture<Void> swapAsync(Profile profile, Supplier<? extends Component> factory) {
        return core.swapAsync(profile, factory);
    }

    @Override
    public CompletableFuture<SwapTimings> swapAsync(Profile profile, Supplier<? extends Component> factory,
                                                    LongConsumer onFirstHandling) {
        return core.swapAsync(profile, factory, onFirstHandling);
    }

    @Override
    public CompletableFuture<SwapTimings> swapAsync(Profile profile, Supplier<? extends Component> factory,
                                                    LongConsumer onFirstHandling, Duration settleWait) {
        return core.swapAsync(profile, factory, onFirstHandling, settleWait);
    }

    @Override
    public Shell addHeld(Profile profile, Profile arrival, Supplier<? extends Component> factory,
                         LongConsumer onFirstHandling) {
        return core.addHeld(profile, arrival, factory, onFirstHandling);
    }

    @Override
    public void admit(Profile arrival, long forwardedCount) {
        core.admit(arrival, forwardedCount);
    }

    @Override
    public CompletableFuture<ComponentState> snapshotAsync(Profile profile) {
        return core.snapshotAsync(profile);
    }

    @Override
    public CompletableFuture<Void> relocateAsync(Profile profile, RemoteRoute route) {
        return core.relocateAsync(profile, route);
    }

    @Override
    public Shell reinstate(Shell relocated, ComponentState state) throws Exception {
        return core.reinstate(relocated, state);
    }

    @Override
    public ContentsTypes contentsTypes() {
        return core.contentsTypes();
    }

    @Override
    public NodeStats stats() {
        return core.stats();
    }

    /** {@return the node's scheduler (e.g. to learn the priorities of its dispatchers)} */
    @Override
    public Scheduler scheduler() {
        return core.scheduler();
    }

    @Override
    public long queuedBytesFrom(String viaNodeId) {
        return core.queuedBytesFrom(viaNodeId);
    }

    @Override
    public String toString() {
        return "EtherwareNode[" + core.nodeId() + "]";
    }

    /**
     * Builds a node: the {@link NodeConfig.Builder} settings, then {@link #build()}. Not
     * thread-safe.
     */
    public static final class Builder {
        private final NodeConfig.Builder config = NodeConfig.builder();

        Builder() {
        }

        /**
         * This node's id; default {@code node}.
         *
         * @param value an id unique in the system that matches
         *              {@link io.etherware.core.message.Profile#NAME_PATTERN} (checked by
         *              {@link #build()})
         * @return this builder
         */
        public Builder nodeId(String value) {
            config.nodeId(value);
            return this;
        }

        /**
         * The factory of the node's scheduler; default {@code FifoScheduler::new}.
         *
         * @param value makes a new, unstarted scheduler; called once, by {@link #build()}
         * @return this builder
         */
        public Builder scheduler(Supplier<? extends Scheduler> value) {
            config.scheduler(value);
            return this;
        }

        /**
         * The node's clock; default {@link NodeClock#system()}. Tests inject a manual one.
         *
         * @param value the clock of message time stamps and dispatching
         * @return this builder
         */
        public Builder clock(NodeClock value) {
            config.clock(value);
            return this;
        }

        /**
         * The restart policy of components added without their own; default
         * {@link SupervisionPolicy#DEFAULT}.
         *
         * @param value the policy
         * @return this builder
         */
        public Builder supervision(SupervisionPolicy value) {
            config.supervision(value);
            return this;
        }

        /**
         * What the node does when a component exceeds its restart intensity; default
         * {@link Escalation#RESET_ALL}.
         *
         * @param value the node's answer
         * @return this builder
         */
        public Builder escalation(Escalation value) {
            config.escalation(value);
            return this;
        }

        /**
         * Timeout of requests made without one; default 1 s.
         *
         * @param value positive (checked by {@link #build()})
         * @return this builder
         * @throws IllegalArgumentException if it is too long to count in nanoseconds
         */
        public Builder defaultRequestTimeout(Duration value) {
            config.defaultRequestTimeout(value);
            return this;
        }

        /**
         * How long {@link EtherwareNode#close()} lets queued messages be delivered before it
         * discards (and counts) the rest; default 1 s.
         *
         * @param value zero or positive (checked by {@link #build()}); zero discards at once
         * @return this builder
         * @throws IllegalArgumentException if it is too long to count in nanoseconds
         */
        public Builder drainTimeout(Duration value) {
            config.drainTimeout(value);
            return this;
        }

        /**
         * The node's registry of contents types; see {@link NodeConfig.Builder#contentsTypes(ContentsTypes)}.
         *
         * @param value the registry, not null
         * @return this builder
         */
        public Builder contentsTypes(ContentsTypes value) {
            config.contentsTypes(value);
            return this;
        }

        /**
         * Validates the settings and creates the node, not started.
         *
         * @return the node
         * @throws IllegalArgumentException naming the setting, its value and a fix if one is out of
         *                                  range
         * @throws NullPointerException     naming the setting if a required one was set to null
         */
        public EtherwareNode build() {
            return new EtherwareNode(config.build());
        }
    }
}
