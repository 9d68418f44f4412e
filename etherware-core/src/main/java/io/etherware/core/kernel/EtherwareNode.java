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
public final class EtherwareNode implements Kernel, AutoCloseable {

    private static final Logger log = LoggerFactory.getLogger(Kernel.class);

    private final KernelCore core;

    private EtherwareNode(NodeConfig config) {
        this.core = new KernelCore(config);
    }

    /** A builder with the defaults of {@link NodeConfig.Builder}. */
    public static Builder builder() {
        return new Builder();
    }

    /** A node with the given configuration, not started. */
    public static EtherwareNode create(NodeConfig config) {
        return new EtherwareNode(config);
    }

    /**
     * Registers the kernel's notices ({@code undeliverable}, {@code request-failed}) in a
     * contents registry. A node does this for its own registry ({@link #contentsTypes()}); call it
     * for a codec built apart from a node that must read a node's notices.
     */
    public static void registerContents(ContentsTypes types) {
        KernelCore.registerContents(types);
    }

    public NodeConfig config() {
        return core.config();
    }

    // ---------------------------------------------------------------- lifecycle

    /** Starts the scheduler, then the components in registration order. Once. */
    public EtherwareNode start() {
        core.start();
        return this;
    }

    /**
     * Adds a component with the node's default supervision policy; starts it now if the node
     * runs. {@code factory} makes the first instance now and new ones for restarts.
     *
     * @throws IllegalArgumentException if the profile is already registered
     */
    public Shell add(Profile profile, Supplier<? extends Component> factory) {
        return core.add(profile, factory, core.config().supervision());
    }

    /** Adds a component with its own supervision policy. */
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

    /** {@link #removeAsync} and wait until the component has stopped. */
    public void remove(Profile profile) {
        await(removeAsync(profile), "remove", profile);
    }

    /** The shell of a local component (exact profile or an unambiguous query). */
    public Shell shell(Profile profile) {
        return core.shell(profile);
    }

    /** The registered local components, in registration order. */
    public List<Shell> shells() {
        return core.shells();
    }

    public boolean isRunning() {
        return core.isRunning();
    }

    public boolean isClosed() {
        return core.isClosed();
    }

    /** Closes the node on a new thread (usable from a component); completes when it is closed. */
    public CompletableFuture<Void> closeAsync() {
        return core.closeAsync();
    }

    /** Completes when the node has closed, whoever closed it (escalation may). */
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

    /** Sends best-effort contents from outside any component (no sender). */
    public MessageId send(Profile to, Contents contents) {
        return send(to, contents, QoS.NONE);
    }

    /** Sends contents from outside any component (no sender: nobody gets a notice if it is lost). */
    public MessageId send(Profile to, Contents contents, QoS qos) {
        MessageId id = core.newMessageId();
        core.send(new Message(to, null, core.clock().epochNanos(), qos, contents, id, null));
        return id;
    }

    /** A request from outside with the default timeout; see {@link Kernel#request}. */
    public CompletableFuture<Message> request(Profile to, Contents contents) {
        return request(to, contents, QoS.NONE, core.config().defaultRequestTimeoutNs());
    }

    /** A request from outside; the node's {@link #profile()} is its sender. */
    public CompletableFuture<Message> request(Profile to, Contents contents, QoS qos, long timeoutNs) {
        return core.request(outsideMessage(to, contents, qos), timeoutNs);
    }

    /** A blocking request from outside with the default timeout. */
    public Message requestBlocking(Profile to, Contents contents) {
        return requestBlocking(to, contents, QoS.NONE, core.config().defaultRequestTimeoutNs());
    }

    /**
     * A blocking request from outside.
     *
     * @throws io.etherware.core.component.RequestFailedException if no reply comes
     * @throws IllegalStateException on a dispatcher thread
     */
    public Message requestBlocking(Profile to, Contents contents, QoS qos, long timeoutNs) {
        return core.requestBlocking(outsideMessage(to, contents, qos), timeoutNs);
    }

    private Message outsideMessage(Profile to, Contents contents, QoS qos) {
        return new Message(to, core.profile(), core.clock().epochNanos(), qos, contents, core.newMessageId(), null);
    }

    // ---------------------------------------------------------------- management, blocking forms

    /** {@link #holdAsync} and wait for the component's message boundary. */
    public void hold(Profile profile) {
        await(holdAsync(profile), "hold", profile);
    }

    /**
     * {@link #swapAsync} and wait.
     *
     * @throws IllegalStateException carrying the error if the swap was rolled back
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
    public ContentsTypes contentsTypes() {
        return core.contentsTypes();
    }

    @Override
    public NodeStats stats() {
        return core.stats();
    }

    /** The node's scheduler (e.g. to learn the priorities of its dispatchers). */
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

        public Builder nodeId(String value) {
            config.nodeId(value);
            return this;
        }

        public Builder scheduler(Supplier<? extends Scheduler> value) {
            config.scheduler(value);
            return this;
        }

        public Builder clock(NodeClock value) {
            config.clock(value);
            return this;
        }

        public Builder supervision(SupervisionPolicy value) {
            config.supervision(value);
            return this;
        }

        public Builder escalation(Escalation value) {
            config.escalation(value);
            return this;
        }

        public Builder defaultRequestTimeout(Duration value) {
            config.defaultRequestTimeout(value);
            return this;
        }

        public Builder drainTimeout(Duration value) {
            config.drainTimeout(value);
            return this;
        }

        /** See {@link NodeConfig.Builder#contentsTypes(ContentsTypes)}. */
        public Builder contentsTypes(ContentsTypes value) {
            config.contentsTypes(value);
            return this;
        }

        /** The node, configured and validated, not started. */
        public EtherwareNode build() {
            return new EtherwareNode(config.build());
        }
    }
}
