package io.etherware.core.kernel.internal;

import io.etherware.core.component.Component;
import io.etherware.core.component.ComponentState;
import io.etherware.core.component.Shell;
import io.etherware.core.kernel.ComponentHost;
import io.etherware.core.kernel.Endpoint;
import io.etherware.core.kernel.ProfileResolutionException;
import io.etherware.core.kernel.Kernel;
import io.etherware.core.kernel.MessageTap;
import io.etherware.core.kernel.NodeConfig;
import io.etherware.core.kernel.NodeStats;
import io.etherware.core.kernel.OrderMarker;
import io.etherware.core.kernel.ProfileRegistry;
import io.etherware.core.kernel.RemoteRoute;
import io.etherware.core.kernel.RequestFailed;
import io.etherware.core.kernel.SupervisionPolicy;
import io.etherware.core.kernel.SwapTimings;
import io.etherware.core.kernel.Undeliverable;
import io.etherware.core.message.ContentsTypes;
import io.etherware.core.message.Message;
import io.etherware.core.message.MessageId;
import io.etherware.core.message.Profile;
import io.etherware.core.scheduler.Job;
import io.etherware.core.scheduler.JobRunner;
import io.etherware.core.scheduler.Scheduler;
import io.etherware.core.time.NodeClock;
import java.time.Duration;
import java.util.Comparator;
import java.util.List;
import java.util.Objects;
import java.util.concurrent.CompletableFuture;
import java.util.concurrent.atomic.AtomicLong;
import java.util.concurrent.atomic.AtomicReference;
import java.util.function.LongConsumer;
import java.util.function.Supplier;
import org.slf4j.Logger;
import org.slf4j.LoggerFactory;

/**
 * The kernel of a node (paper Section III-A): resolves profiles, runs jobs through the component
 * gates ({@link LocalShell}), and keeps the node's lifecycle and the entry and exit of its
 * components. Its parts, each given what it needs when the kernel is built: {@link Delivery} (what
 * becomes of a message once its destination is resolved: a job, a route, an undeliverable notice),
 * {@link RequestTable} (requests and their replies), {@link ShellTable} (the hosted components and
 * their counters), {@link Supervision} (failure reports, escalation), {@link Reconfiguration}
 * (hold, swap, snapshot, relocation) and {@link Taps}.
 *
 * <p>The per-message path ({@link #send}, {@link #run}) takes no lock when the receiver is free,
 * logs nothing and allocates only the job (the sender allocates the message).
 *
 * <p>Thread-safety: every method may be called from any thread; lifecycle changes are serialized
 * on the lifecycle lock, held while the node starts or begins to close and while a component is
 * made and registered or unregistered (inside it, {@link ProfileTable} takes its own).
 */
public final class KernelCore implements ComponentHost, JobRunner {

    private static final Logger log = LoggerFactory.getLogger(Kernel.class);

    private enum NodeState { CREATED, RUNNING, CLOSING, CLOSED }

    private final NodeConfig config;
    private final String nodeId;
    private final NodeClock clock;
    private final Profile nodeProfile;
    private final Scheduler scheduler;
    private final Comparator<Job> urgency;
    private final ProfileTable registry = new ProfileTable();
    private final RequestTable requests;
    private final Reconfiguration reconfiguration;
    /** Jobs, routes and undeliverable notices for resolved messages. */
    private final Delivery delivery;
    /** What sees every message sent. */
    private final Taps taps;
    private final AtomicLong messageSequence = new AtomicLong();
    /** The components this node hosts, and the counters of those it hosted. */
    private final ShellTable shells = new ShellTable(registry);
    /** Failure reports and escalation. */
    private final Supervision supervision;
    private final Object lifecycleLock = new Object();
    private final CompletableFuture<Void> closed = new CompletableFuture<>();
    private volatile NodeState state = NodeState.CREATED;

    public KernelCore(NodeConfig config) {
        this.config = Objects.requireNonNull(config, "config");
        this.nodeId = config.nodeId();
        this.clock = config.clock();
        this.nodeProfile = Profile.of("etherware.node", "id", nodeId);
        this.scheduler = Objects.requireNonNull(config.scheduler().get(), "the scheduler factory returned null");
        // Ties in arrival order, whatever the scheduler's comparator does with them.
        this.urgency = scheduler.urgency().thenComparingLong(Job::sequence);
        this.delivery = new Delivery(nodeId, nodeProfile, clock, scheduler, this::send, this::newMessageId,
                this::isClosing);
        this.requests = new RequestTable(nodeId, delivery::deliverOutcome, this::mayAnswer, this::send);
        this.reconfiguration = new Reconfiguration(clock, registry, requests);
        this.supervision = new Supervision(nodeId, clock, config.escalation(), requests, shells, this::send,
                this::newMessageId, this::closeAsync);
        this.taps = new Taps(nodeId);
        registerContents(config.contentsTypes());
    }

    /**
     * Registers the kernel's notices ({@code undeliverable}, {@code request-failed}) and markers
     * ({@code order-marker}) in {@code types}.
     */
    public static void registerContents(ContentsTypes types) {
        types.register("undeliverable", Undeliverable.class);
        types.register("request-failed", RequestFailed.class);
        types.register("order-marker", OrderMarker.class);
    }

    // ---------------------------------------------------------------- Kernel

    @Override
    public String nodeId() {
        return nodeId;
    }

    @Override
    public Profile profile() {
        return nodeProfile;
    }

    @Override
    public NodeClock clock() {
        return clock;
    }

    @Override
    public ProfileRegistry registry() {
        return registry;
    }

    public NodeConfig config() {
        return config;
    }

    @Override
    public Scheduler scheduler() {
        return scheduler;
    }

    Comparator<Job> urgency() {
        return urgency;
    }

    @Override
    public MessageId newMessageId() {
        return new MessageId(nodeId, messageSequence.getAndIncrement());
    }

    @Override
    public void send(Message message) {
        if (state == NodeState.CREATED) {
            throw new IllegalStateException("node '" + nodeId + "' is not started: call start() before sending");
        }
        taps.tell(message);
        MessageId correlationId = message.correlationId();
        if (correlationId != null && nodeId.equals(correlationId.nodeId()) && requests.interceptReply(message)) {
            return;
        }
        Endpoint endpoint = registry.lookup(message.profile());
        if (endpoint instanceof Endpoint.Local local) {
            delivery.enqueue(message, (LocalShell) local.shell());
        } else if (endpoint instanceof Endpoint.Remote remote) {
            delivery.deliverRemote(message, remote.route());
        } else {
            delivery.undeliverable(message, registry.explainMiss(message.profile()));
        }
    }

    /** Adds a tap; see {@link MessageTap}. */
    public void addTap(MessageTap tap) {
        taps.add(tap);
    }

    /** Removes a tap; it sees no message sent after this returns. */
    public boolean removeTap(MessageTap tap) {
        return taps.remove(tap);
    }

    /**
     * Whether node {@code nodeId} may answer {@code request}: its profile resolves to a route that
     * leads there (or will, when a node waiting to take it over does).
     */
    private boolean mayAnswer(Message request, String nodeId) {
        try {
            return registry.resolve(request.profile()) instanceof Endpoint.Remote remote
                    && remote.route().isServedBy(nodeId);
        } catch (ProfileResolutionException e) {
            return false;
        }
    }

    @Override
    public long queuedBytesFrom(String viaNodeId) {
        return delivery.queuedBytesFrom(viaNodeId);
    }

    @Override
    public CompletableFuture<Message> request(Message request, long timeoutNs) {
        Message withSender = request.hasSender() ? request
                : new Message(request.profile(), nodeProfile, request.timeStamp(), request.qos(), request.contents(),
                        request.messageId(), request.correlationId(), request.origin());
        return request(withSender, null, timeoutNs);
    }

    /**
     * Sends a request; the outcome is delivered as a job of {@code requester} (null: completed on
     * the thread that has it).
     */
    CompletableFuture<Message> request(Message request, LocalShell requester, long timeoutNs) {
        return requests.send(request, requester, timeoutNs);
    }

    /** A request that waits for its reply; refuses dispatcher threads. */
    public Message requestBlocking(Message request, long timeoutNs) {
        DispatcherMark.requireNotDispatcher("requestBlocking",
                "Use request(...) and continue in the future's callback (thenAccept).");
        return RequestTable.await(request(request, timeoutNs), request.messageId(), timeoutNs);
    }

    @Override
    public CompletableFuture<Void> holdAsync(Profile profile) {
        LocalShell shell = shells.local(profile);
        IllegalStateException arriving = shell.stillArriving("hold");
        return arriving != null ? CompletableFuture.failedFuture(arriving) : reconfiguration.holdAsync(shell);
    }

    @Override
    public CompletableFuture<Void> holdAsync(Profile profile, Duration settleWait) {
        LocalShell shell = shells.local(profile);
        IllegalStateException arriving = shell.stillArriving("hold");
        return arriving != null ? CompletableFuture.failedFuture(arriving)
                : reconfiguration.holdAsync(shell, settleWait);
    }

    @Override
    public void release(Profile profile) {
        shells.local(profile).release();
    }

    @Override
    public CompletableFuture<Void> swapAsync(Profile profile, Supplier<? extends Component> factory) {
        Objects.requireNonNull(factory, "factory");
        return reconfiguration.swapAsync(shells.local(profile), factory, null, Duration.ZERO).thenApply(timings -> null);
    }

    @Override
    public CompletableFuture<SwapTimings> swapAsync(Profile profile, Supplier<? extends Component> factory,
                                                    LongConsumer onFirstHandling) {
        return swapAsync(profile, factory, onFirstHandling, Duration.ZERO);
    }

    @Override
    public CompletableFuture<SwapTimings> swapAsync(Profile profile, Supplier<? extends Component> factory,
                                                    LongConsumer onFirstHandling, Duration settleWait) {
        Objects.requireNonNull(factory, "factory");
        Objects.requireNonNull(onFirstHandling, "onFirstHandling");
        return reconfiguration.swapAsync(shells.local(profile), factory, onFirstHandling, settleWait);
    }

    @Override
    public ContentsTypes contentsTypes() {
        return config.contentsTypes();
    }

    @Override
    public NodeStats stats() {
        ShellTable.Totals totals = shells.totals();
        return new NodeStats(nodeId, delivery.jobCount(), totals.handled(), totals.failed(), totals.restarts(),
                delivery.undeliverableCount(), delivery.discardedCount(),
                requests.timeoutCount(), requests.lateReplyCount(), supervision.escalationCount(), supervision.resetCount());
    }

    // ---------------------------------------------------------------- JobRunner

    @Override
    public boolean run(Job job, long nowNs) {
        DispatcherMark.markCurrentThread();
        Object target = job.target();
        LocalShell shell = target instanceof LocalShell local ? local : ((PendingRequest) target).requester;
        if (!job.isReserved() && !shell.acquireOrPark(job)) {
            return false;
        }
        shell.execute(job, nowNs);
        return true;
    }

    /** See {@link Delivery#resubmit}. */
    boolean resubmit(Job job) {
        return delivery.resubmit(job);
    }

    /** See {@link Delivery#discard}. */
    void discard(Job job) {
        delivery.discard(job);
    }

    // ---------------------------------------------------------------- parts the shells use

    /** Jobs, routes and undeliverable notices, for the shells. */
    Delivery delivery() {
        return delivery;
    }

    /** Failure reports and escalation, for the shells. */
    Supervision supervision() {
        return supervision;
    }

    // ---------------------------------------------------------------- lifecycle

    /** Adds a component; starts it at once if the node runs. */
    @Override
    public Shell addHeld(Profile profile, Profile arrival, Supplier<? extends Component> factory,
                         LongConsumer onFirstHandling) {
        Objects.requireNonNull(profile, "profile");
        Objects.requireNonNull(arrival, "arrival");
        Objects.requireNonNull(onFirstHandling, "onFirstHandling");
        LocalShell shell;
        synchronized (lifecycleLock) {
            if (state != NodeState.RUNNING) {
                throw new IllegalStateException("node '" + nodeId + "' is " + state + "; a migrated component arrives"
                        + " only at a running node");
            }
            shell = new LocalShell(this, profile, factory, config.supervision());
            shells.addArrived(shell, arrival, onFirstHandling);
        }
        shell.start();
        return shell;
    }

    @Override
    public void admit(Profile arrival, long forwardedCount) {
        shells.arrivedAs(arrival).admitAfter(forwardedCount);
    }

    @Override
    public CompletableFuture<Void> removeAsync(Profile profile) {
        return remove(profile);
    }

    public Shell add(Profile profile, Supplier<? extends Component> factory, SupervisionPolicy policy) {
        LocalShell shell;
        boolean startNow;
        synchronized (lifecycleLock) {
            if (state == NodeState.CLOSING || state == NodeState.CLOSED) {
                throw new IllegalStateException("node '" + nodeId + "' is closed; cannot add '" + profile + "'");
            }
            shell = new LocalShell(this, profile, factory, policy);
            shells.add(shell);
            startNow = state == NodeState.RUNNING;
        }
        if (startNow) {
            shell.start();
        }
        return shell;
    }

    /**
     * Removes a component: unregisters it at once (new messages for the profile are resolved
     * anew), then stops it at its next message boundary. Messages that waited for it are
     * resolved anew as well, so they follow the profile if it is registered elsewhere.
     */
    public CompletableFuture<Void> remove(Profile profile) {
        Objects.requireNonNull(profile, "profile");
        LocalShell shell;
        synchronized (lifecycleLock) {
            shell = shells.remove(profile);
        }
        return shells.stop(shell);
    }

    @Override
    public CompletableFuture<Void> relocateAsync(Profile profile, RemoteRoute route) {
        Objects.requireNonNull(route, "route");
        LocalShell shell = shells.local(profile);
        if (!shell.profile().equals(profile)) {
            throw new IllegalArgumentException("relocate needs the exact profile '" + shell.profile() + "', not a query");
        }
        IllegalStateException arriving = shell.stillArriving("relocate");
        if (arriving != null) {
            throw arriving;
        }
        return reconfiguration.relocateAsync(shell, route, () -> shells.detach(shell))
                .thenRun(() -> shells.retire(shell));
    }

    @Override
    public Shell reinstate(Shell relocated, ComponentState state) throws Exception {
        if (!(relocated instanceof LocalShell old) || !old.relocatedBy(this)) {
            throw new IllegalArgumentException("'" + (relocated == null ? null : relocated.profile()) + "' is not a"
                    + " component that node '" + nodeId + "' relocated");
        }
        if (!old.hasSwitched()) {
            throw new IllegalStateException("the relocation of '" + old.profile() + "' has not pointed its profile"
                    + " at the route (yet)");
        }
        if (this.state != NodeState.RUNNING) {
            throw new IllegalStateException("node '" + nodeId + "' is " + this.state + "; cannot reinstate '"
                    + old.profile() + "'");
        }
        Supplier<? extends Component> factory = old.factory();
        Component first = Objects.requireNonNull(factory.get(), "the factory of '" + old.profile() + "' returned null");
        if (state != null) {
            first.restore(state);
        }
        if (!old.claimReinstatement()) {
            throw new IllegalStateException("'" + old.profile() + "' was reinstated already");
        }
        var unused = new AtomicReference<Component>(first);
        return add(old.profile(), () -> {
            Component restored = unused.getAndSet(null);
            return restored != null ? restored : factory.get();
        }, old.policy());
    }

    @Override
    public CompletableFuture<ComponentState> snapshotAsync(Profile profile) {
        return reconfiguration.snapshotAsync(shells.local(profile));
    }

    public Shell shell(Profile profile) {
        return shells.local(profile);
    }

    public List<Shell> shells() {
        return List.copyOf(shells.registered());
    }

    /** Starts the scheduler, then the components in registration order. */
    public void start() {
        synchronized (lifecycleLock) {
            if (state != NodeState.CREATED) {
                throw new IllegalStateException("node '" + nodeId + "' is " + state + "; start() works once");
            }
            scheduler.start(this, clock);
            state = NodeState.RUNNING;
        }
        for (LocalShell shell : shells.registered()) {
            shell.start();
        }
        log.info("node {} started: scheduler {}, {} components", nodeId, scheduler.name(), shells.registered().size());
    }

    public boolean isRunning() {
        return state == NodeState.RUNNING;
    }

    public boolean isClosed() {
        return state == NodeState.CLOSED;
    }

    private boolean isClosing() {
        NodeState now = state;
        return now == NodeState.CLOSING || now == NodeState.CLOSED;
    }

    /** Completes when the node has closed. */
    @Override
    public CompletableFuture<Void> closedFuture() {
        return closed;
    }

    /** Closes on a new thread; usable from dispatcher threads. */
    public CompletableFuture<Void> closeAsync() {
        if (state != NodeState.CLOSING && state != NodeState.CLOSED) {
            Thread.ofPlatform().name("etherware-close-" + nodeId).start(this::close);
        }
        return closed;
    }

    /**
     * Drains the scheduler for at most the drain timeout, counts what remains as discarded,
     * stops the components in reverse registration order and fails the waiting requests.
     */
    public void close() {
        boolean wasStarted;
        boolean closing;
        synchronized (lifecycleLock) {
            closing = state == NodeState.CLOSING || state == NodeState.CLOSED;
            if (!closing) {
                DispatcherMark.requireNotDispatcher("close()", "Use closeAsync().");
            }
            wasStarted = state == NodeState.RUNNING;
            state = closing ? state : NodeState.CLOSING;
        }
        if (closing) {
            if (!DispatcherMark.isDispatcherThread()) {
                closed.join(); // another thread closes; return once it is done
            }
            return;
        }
        try {
            if (wasStarted) {
                for (Job job : scheduler.shutdown(config.drainTimeoutNs())) {
                    delivery.discard(job);
                }
            }
            shells.closeAll(delivery::discard);
            requests.close();
        } finally {
            state = NodeState.CLOSED;
            closed.complete(null);
        }
        log.info("node {} closed: {}", nodeId, stats());
    }
}
