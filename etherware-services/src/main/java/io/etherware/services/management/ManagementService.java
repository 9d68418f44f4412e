package io.etherware.services.management;

import io.etherware.core.component.Component;
import io.etherware.core.component.ComponentContext;
import io.etherware.core.component.Shell;
import io.etherware.core.kernel.ComponentHost;
import io.etherware.core.kernel.Endpoint;
import io.etherware.core.kernel.EtherwareNode;
import io.etherware.core.kernel.ProfileResolutionException;
import io.etherware.core.kernel.SwapTimings;
import io.etherware.core.message.Criticality;
import io.etherware.core.message.QoS;
import io.etherware.core.message.Message;
import io.etherware.core.message.Profile;
import io.etherware.services.management.AccessRule.Operation;
import io.etherware.services.management.ManagementFailure.Reason;
import io.etherware.services.management.internal.AccessControl;
import io.etherware.services.management.internal.ImplementationLoader;
import io.etherware.services.management.internal.LoadFailure;
import io.etherware.services.management.internal.MigrationSource;
import io.etherware.services.management.internal.MigrationTarget;
import io.etherware.services.network.NetworkMessenger;
import java.net.URLClassLoader;
import java.time.Duration;
import java.util.Map;
import java.util.Objects;
import java.util.concurrent.CompletableFuture;
import java.util.concurrent.CompletionException;
import java.util.concurrent.ConcurrentHashMap;
import java.util.concurrent.Executor;
import java.util.concurrent.ExecutionException;
import java.util.concurrent.ExecutorService;
import java.util.concurrent.Executors;
import java.util.concurrent.RejectedExecutionException;
import java.util.concurrent.TimeUnit;
import java.util.concurrent.TimeoutException;
import java.util.concurrent.atomic.AtomicBoolean;
import java.util.concurrent.atomic.AtomicInteger;
import java.util.concurrent.atomic.AtomicReference;
import java.util.concurrent.atomic.LongAdder;
import java.util.function.BiConsumer;
import java.util.function.Consumer;
import org.slf4j.Logger;

/**
 * A node's management service (paper Section VI-C): a component at
 * {@code etherware.management[node=<id>]} that serves {@link UpgradeRequest}s and
 * {@link MigrateRequest}s for the node's own components, answering each with an
 * {@link UpgradeResult}, a {@link MigrationResult} or a {@link ManagementFailure}, and the
 * {@link MigrationStep}s of migrations coming to this node.
 *
 * <h2>An upgrade, step by step</h2>
 * <ol>
 *   <li>On the service's dispatcher: refuse a request that arrived from another node unless the
 *       {@link ManagementConfig access list} lets that node upgrade that component (the rule is on
 *       {@link ManagementConfig}), then hand the work to the service's own worker thread; the
 *       dispatcher is free again at once.</li>
 *   <li>On the worker: resolve the component, load and check the class (from the class path, or
 *       from an allowlisted jar signed by a trusted key, see {@link Implementation}) and construct
 *       its first instance.</li>
 *   <li>Back on the service's dispatcher (the worker sends the loaded logic to the service as a
 *       local message carrying the request's QoS, so the swap starts at the request's priority,
 *       paper Section VI-C1):
 *       {@link ComponentHost#swapAsync(Profile, java.util.function.Supplier, java.util.function.LongConsumer)}
 *       without waiting for it. At the component's next message boundary the kernel snapshots the
 *       old logic, restores the state into the new one ({@code restore} sees the state's
 *       {@code schemaVersion()}), starts it and swaps it in; messages arriving meanwhile wait and
 *       are then delivered in order, exactly once. If the snapshot, {@code restore} or
 *       {@code onStart} throws, the old logic resumes and the answer is {@link Reason#ROLLED_BACK}
 *       with the cause.</li>
 *   <li>The answer waits (without blocking anything) for the new logic's first message, at most
 *       {@link ManagementConfig#firstMessageWaitNs()} after loading, to report the swap gap; it is
 *       assembled and sent on the worker.</li>
 * </ol>
 *
 * <p>Threading: {@link #onMessage} runs on a dispatcher and never blocks or loads code there.
 * Loading and answering run on one worker thread per service, so upgrades are loaded one at a
 * time; requests queue for it in arrival order, at most
 * {@link ManagementConfig#maxQueuedOperations()} waiting, and one beyond that is answered at once
 * with {@link Reason#BUSY} (counted, {@link #busyCount()}). The swap runs where the kernel puts
 * it: on the service's dispatcher if the component is between messages and awaits no reply, else
 * on the component's dispatcher right after a later message (see
 * {@link ManagementConfig#settleWaitNs()}). Either
 * way the new logic's {@code restore} and {@code onStart} run on a dispatcher and should be quick.
 *
 * <h2>A migration</h2>
 * The steps and the ordering argument are in the package documentation. At the source, the whole
 * migration runs on the worker, which waits for the target's answers (so a node runs one management
 * operation at a time; the next wait in the same queue). At the target, PREPARE (loading,
 * constructing) runs on a second thread of the service, with a queue of the same bound, and the
 * answers that wait for a first message are assembled there too: two nodes migrating components
 * to each other at once each serve the other's steps while their own migration waits; INSTALL
 * ({@code restore}, {@code onStart}, registration) and HANDOVER run on the service's dispatcher,
 * because they are on the migration gap's path. Migrating from this node needs the
 * {@link NetworkMessenger} given to {@link #install(EtherwareNode, ManagementConfig, NetworkMessenger)}.
 */
public final class ManagementService implements Component {

    private static final String UPGRADE = "upgrade";
    private static final String MIGRATE = "migrate";

    private final ComponentHost kernel;
    private final ManagementConfig config;
    private final NetworkMessenger network;
    private final ImplementationLoader loader;
    private final AccessControl access;
    /** The jar class loader behind each component upgraded from a jar; closed when replaced. */
    private final Map<Profile, URLClassLoader> jarLoaders;
    private final Counters counters;
    /** Upgrades' loading and migrations away from this node: one at a time, in arrival order. */
    private ExecutorService worker;
    /** PREPARE steps of migrations into this node: apart, so two nodes migrating to each other go on. */
    private ExecutorService steps;
    /** Requests handed to the worker and not yet answered or done (the one in progress included). */
    private final AtomicInteger operationsIn = new AtomicInteger();
    /** PREPARE steps handed to the steps thread and not yet answered. */
    private final AtomicInteger stepsIn = new AtomicInteger();
    private Executor continuations;
    private MigrationSource migrationSource;
    private MigrationTarget migrationTarget;
    private ComponentContext context;
    private Logger log;

    /**
     * A service managing the components of {@code kernel}'s node; add it at
     * {@link Management#profileOf}, or use {@link #install}. It cannot migrate components away
     * from this node, but can be the target of a migration.
     *
     * @param kernel the node whose components it manages
     * @param config its allowlist, trusted signers, access list and timeouts
     */
    public ManagementService(ComponentHost kernel, ManagementConfig config) {
        this(kernel, config, null);
    }

    /**
     * A service managing the components of {@code kernel}'s node, able to migrate them to the
     * nodes {@code network} connects it to (null: no migrations from this node; it can still be
     * the target of one).
     *
     * @param kernel  the node whose components it manages
     * @param config  its allowlist, trusted signers, access list and timeouts
     * @param network the node's started messenger, or null
     */
    public ManagementService(ComponentHost kernel, ManagementConfig config, NetworkMessenger network) {
        this(kernel, config, network, new Counters(), new ConcurrentHashMap<>());
    }

    private ManagementService(ComponentHost kernel, ManagementConfig config, NetworkMessenger network,
                              Counters counters, Map<Profile, URLClassLoader> jarLoaders) {
        this.kernel = Objects.requireNonNull(kernel, "kernel");
        this.config = Objects.requireNonNull(config, "config");
        Management.registerContents(kernel.contentsTypes());
        this.network = network;
        this.loader = new ImplementationLoader(config.allowlist(), config.trustedSigners(), config.classLoader(),
                kernel.contentsTypes());
        this.access = new AccessControl(kernel, config);
        this.counters = counters;
        this.jarLoaders = jarLoaders;
    }

    /**
     * Adds a management service to {@code node} at {@code etherware.management[node=<id>]},
     * without migrations from this node.
     *
     * @param node   the node whose components it manages
     * @param config its allowlist, trusted signers, access list and timeouts
     * @return the service; if its supervision restarts it, the new instances share its counters
     */
    public static ManagementService install(EtherwareNode node, ManagementConfig config) {
        return install(node, config, null);
    }

    /**
     * Adds a management service to {@code node} that can also migrate its components to the
     * nodes {@code network} connects it to. Start the messenger first.
     *
     * @param node    the node whose components it manages
     * @param config  its allowlist, trusted signers, access list and timeouts
     * @param network the node's started messenger, or null for no migrations from this node
     * @return the service; if its supervision restarts it, the new instances share its counters
     */
    public static ManagementService install(EtherwareNode node, ManagementConfig config, NetworkMessenger network) {
        var first = new ManagementService(node, config, network);
        var unused = new AtomicReference<>(first);
        node.add(Management.profileOf(node.nodeId()), () -> {
            ManagementService instance = unused.getAndSet(null);
            return instance != null ? instance
                    : new ManagementService(node, config, network, first.counters, first.jarLoaders);
        });
        return first;
    }

    /**
     * Starts the service's two threads (the worker, for upgrades' loading and answering and for
     * migrations away; and one for the PREPARE steps of migrations into this node). Called by the
     * kernel when the service starts or restarts.
     *
     * @param context the service's context; its logger and replies are used from here on
     */
    @Override
    public void onStart(ComponentContext context) {
        this.context = context;
        this.log = context.logger();
        this.worker = Executors.newSingleThreadExecutor(Thread.ofPlatform().daemon()
                .name("etherware-management-" + kernel.nodeId()).factory());
        this.steps = Executors.newSingleThreadExecutor(Thread.ofPlatform().daemon()
                .name("etherware-management-steps-" + kernel.nodeId()).factory());
        this.continuations = inlineWhenRefused(worker);
        this.migrationSource = new MigrationSource(kernel, config, network, access);
        // The answers of steps into this node must not wait for this node's own migration away,
        // which may be waiting for the other node's answers.
        this.migrationTarget = new MigrationTarget(kernel, config, loader, inlineWhenRefused(steps), this::installed);
    }

    /** Runs a task on {@code pool}, or where it completes if the pool has stopped. */
    private static Executor inlineWhenRefused(ExecutorService pool) {
        // After onStop, an operation in flight still answers: on the thread that completes it.
        return task -> {
            try {
                pool.execute(task);
            } catch (RejectedExecutionException refused) {
                task.run();
            }
        };
    }

    /**
     * Gives back a request's place in its queue, once: before its answer is sent, so that whoever
     * asks again on that answer finds the place free.
     */
    private static final class Permit {
        private final AtomicInteger in;
        private final AtomicBoolean released = new AtomicBoolean();

        Permit(AtomicInteger in) {
            this.in = in;
        }

        void release() {
            if (released.compareAndSet(false, true)) {
                in.decrementAndGet();
            }
        }
    }

    /**
     * Hands {@code task} to {@code pool} if fewer than {@link ManagementConfig#maxQueuedOperations()}
     * wait besides the one in progress ({@code in} counts them); otherwise, or if the service stops,
     * answers the request through {@code failure} (BUSY with the bound, or SERVICE_FAILED). The
     * task releases its permit before it answers.
     */
    private void submit(ExecutorService pool, AtomicInteger in, Consumer<Permit> task,
                           BiConsumer<Reason, String> failure) {
        if (in.incrementAndGet() > 1 + config.maxQueuedOperations()) {
            in.decrementAndGet();
            counters.busy.increment();
            failure.accept(Reason.BUSY, "the management service of node '" + kernel.nodeId() + "' has "
                    + config.maxQueuedOperations() + " operations waiting behind the one in progress"
                    + " (maxQueuedOperations); nothing was done: ask again later");
            return;
        }
        var permit = new Permit(in);
        try {
            pool.execute(() -> {
                try {
                    task.accept(permit);
                } finally {
                    permit.release();
                }
            });
        } catch (RejectedExecutionException e) {
            permit.release();
            failure.accept(Reason.SERVICE_FAILED, "the management service of node '" + kernel.nodeId()
                    + "' is stopping");
        }
    }

    @Override
    public void onStop() {
        worker.shutdown();
        steps.shutdown();
    }

    /**
     * Serves one message on the service's dispatcher without blocking: refuses (and counts) what
     * the access list does not allow; hands an upgrade's loading and a migration away from this
     * node to the worker, and a migration's PREPARE step to the steps thread (each queue bounded,
     * BUSY beyond); starts an upgrade's swap and serves a
     * migration's INSTALL and HANDOVER steps here. Anything else with a sender is refused with
     * {@link Reason#BAD_REQUEST}.
     *
     * @param message an {@link UpgradeRequest}, {@link MigrateRequest} or {@link MigrationStep}
     * @param context the service's context
     */
    @Override
    public void onMessage(Message message, ComponentContext context) {
        switch (message.contents()) {
            case UpgradeRequest request -> accept(message, request);
            case MigrateRequest request -> acceptMigration(message, request);
            case MigrationStep step -> acceptStep(message, step);
            case Prepared prepared when context.self().equals(message.sender()) -> swap(prepared);
            default -> {
                if (message.hasSender() && !message.isReply()) {
                    counters.refused.increment();
                    reply(message, new ManagementFailure(message.contents().getClass().getSimpleName(),
                            context.self(), Reason.BAD_REQUEST, "the management service does not serve "
                            + message.contents().getClass().getSimpleName() + " messages; send an UpgradeRequest"));
                } else {
                    log.debug("ignored {} ({})", message.messageId(), message.contents());
                }
            }
        }
    }

    /**
     * Refuses (counts, logs and answers) a request that arrived from another node unless the
     * access list lets that node ask for {@code operation} on {@code target}; see
     * {@link ManagementConfig} for the rule.
     */
    private boolean refused(Message message, Operation operation, String operationName, Profile target) {
        String refusal = access.refusal(message, operation, operationName, target);
        if (refusal == null && message.contents() instanceof MigrationStep step) {
            refusal = access.stepRefusal(message, step);
        }
        if (refusal == null) {
            return false;
        }
        counters.refused.increment();
        log.warn("refused {} request {} of '{}' from node '{}' (sender '{}'): {}", operationName, message.messageId(),
                target, message.origin().nodeId(), message.sender(), refusal);
        reply(message, new ManagementFailure(operationName, target, Reason.REMOTE_REFUSED, refusal));
        return true;
    }

    private void accept(Message message, UpgradeRequest request) {
        long receivedNs = kernel.clock().nanoTime();
        if (refused(message, Operation.UPGRADE, UPGRADE, request.target())) {
            return;
        }
        submit(worker, operationsIn, permit -> upgrade(message, request, receivedNs, permit),
                (reason, error) -> fail(message, request, reason, error));
    }

    /**
     * An upgrade loaded by the worker, handed back to the service's dispatcher as a message to
     * itself, carrying the request's QoS: the swap then starts at the request's priority (paper
     * Section VI-C1). Never leaves the node (it is not a registered contents type).
     */
    private record Prepared(Message message, UpgradeRequest request, Shell shell, ImplementationLoader.Loaded loaded,
                            long loadNs, long receivedNs, CompletableFuture<Long> firstHandling,
                            CompletableFuture<Void> swapped)
            implements io.etherware.core.message.Contents {
    }

    /** Worker thread: resolve and load, then hand the swap back to the dispatcher. */
    private void upgrade(Message message, UpgradeRequest request, long receivedNs, Permit permit) {
        Shell shell;
        try {
            shell = localShell(request.target());
        } catch (LoadFailure e) {
            permit.release();
            fail(message, request, e.reason(), e.getMessage());
            return;
        }
        long loadStartNs = kernel.clock().nanoTime();
        ImplementationLoader.Loaded loaded;
        try {
            loaded = loader.load(request.className(), request.jarPath(), request.configuration());
        } catch (LoadFailure e) {
            permit.release();
            fail(message, request, e.reason(), e.getMessage());
            return;
        } catch (RuntimeException | LinkageError e) {
            permit.release();
            fail(message, request, Reason.CLASS_NOT_LOADABLE, "loading '" + request.className() + "' failed: " + e);
            return;
        }
        long loadNs = kernel.clock().nanoTime() - loadStartNs;
        // Armed here, not on the dispatcher: the timer's bookkeeping stays out of the swap gap.
        var firstHandling = new CompletableFuture<Long>();
        firstHandling.completeOnTimeout(SwapTimings.UNKNOWN_NS, config.firstMessageWaitNs(), TimeUnit.NANOSECONDS);
        var swapped = new CompletableFuture<Void>();
        try {
            context.send(context.self(), new Prepared(message, request, shell, loaded, loadNs, receivedNs,
                    firstHandling, swapped), message.qos());
        } catch (RuntimeException e) {
            loaded.discard();
            permit.release();
            fail(message, request, Reason.SERVICE_FAILED, "the management service could not schedule the swap: " + e);
            return;
        }
        // One operation at a time: the next waits until this swap is done (or given up waiting for).
        try {
            swapped.get(config.settleWaitNs() + config.migrationStepTimeoutNs(), TimeUnit.NANOSECONDS);
        } catch (ExecutionException | TimeoutException e) {
            // Answered by the swap's own continuation; the next operation may go.
        } catch (InterruptedException e) {
            Thread.currentThread().interrupt();
        }
    }

    /**
     * Dispatcher: starts the swap without waiting for it. If the component is between messages
     * the swap runs here and now; otherwise the kernel runs it on the component's dispatcher
     * when its current message is done. Nothing else happens here, because until the swap is over
     * (and, on a shared dispatcher, until this handler returns) the component's next message waits:
     * the answer is assembled on the worker once the new logic has begun its first message.
     */
    private void swap(Prepared prepared) {
        Message message = prepared.message();
        UpgradeRequest request = prepared.request();
        Shell shell = prepared.shell();
        ImplementationLoader.Loaded loaded = prepared.loaded();
        String oldImplementation = shell.logicType().getName();
        CompletableFuture<Long> firstHandling = prepared.firstHandling();
        CompletableFuture<SwapTimings> swap;
        try {
            // When no request of the old logic is in flight (within the settle wait): its outcome
            // then reaches the callback that waits for it instead of a replaced logic.
            swap = kernel.swapAsync(shell.profile(), loaded.factory(), firstHandling::complete,
                    Duration.ofNanos(config.settleWaitNs()));
        } catch (RuntimeException e) {
            loaded.discard();
            prepared.swapped().complete(null);
            fail(message, request, Reason.UNKNOWN_COMPONENT, "component '" + shell.profile() + "' went away: " + e);
            return;
        }
        // Not ...Async: on success this runs inside the swap and must cost nothing; only a failure
        // (the slow path) goes to the worker.
        swap.whenComplete((timings, error) -> {
            prepared.swapped().complete(null);
            if (error != null) {
                continuations.execute(() -> rolledBack(message, request, shell, loaded, oldImplementation, error));
            }
        });
        // Runs when both are known: the new logic's first message began (or the wait ended).
        swap.thenAcceptBothAsync(firstHandling, (timings, firstNs) -> {
            installed(shell.profile(), loaded.loader());
            answer(message, shell.profile(), oldImplementation, loaded, prepared.loadNs(), timings, firstNs,
                    prepared.receivedNs());
        }, continuations);
    }

    private void rolledBack(Message message, UpgradeRequest request, Shell shell, ImplementationLoader.Loaded loaded,
                            String oldImplementation, Throwable error) {
        loaded.discard();
        Throwable cause = error instanceof CompletionException && error.getCause() != null ? error.getCause() : error;
        fail(message, request, Reason.ROLLED_BACK, "the swap of '" + shell.profile() + "' to "
                + loaded.type().getName() + " was rolled back, " + oldImplementation + " serves on: " + cause);
    }

    private Shell localShell(Profile target) throws LoadFailure {
        Endpoint endpoint;
        try {
            endpoint = kernel.registry().resolve(target);
        } catch (ProfileResolutionException e) {
            throw new LoadFailure(Reason.UNKNOWN_COMPONENT, e.getMessage());
        }
        if (!(endpoint instanceof Endpoint.Local local)) {
            throw new LoadFailure(Reason.UNKNOWN_COMPONENT, "'" + target + "' is hosted on another node, not on '"
                    + kernel.nodeId() + "'; send the request to that node's management service");
        }
        Shell shell = local.shell();
        if (shell.profile().equals(context.self())) {
            throw new LoadFailure(Reason.BAD_REQUEST, "the management service cannot upgrade or migrate itself");
        }
        if (shell.state() != Shell.State.RUNNING) {
            throw new LoadFailure(Reason.NOT_RUNNING, "component '" + shell.profile() + "' is " + shell.state()
                    + "; only a RUNNING component can be upgraded or migrated");
        }
        return shell;
    }

    // ---------------------------------------------------------------- migration

    private void acceptMigration(Message message, MigrateRequest request) {
        long receivedNs = kernel.clock().nanoTime();
        if (refused(message, Operation.MIGRATE, MIGRATE, request.target())) {
            return;
        }
        submit(worker, operationsIn, permit -> migrate(message, request, receivedNs, permit),
                (reason, error) -> failMigration(message, request.target(), reason, error));
    }

    /** Worker thread: the whole migration, blocking for the target's answers. */
    private void migrate(Message message, MigrateRequest request, long receivedNs, Permit permit) {
        MigrationResult result;
        try {
            Shell shell = localShell(request.target());
            result = migrationSource.migrate(shell, request, receivedNs);
        } catch (LoadFailure e) {
            permit.release();
            failMigration(message, request.target(), e.reason(), e.getMessage());
            return;
        } catch (RuntimeException e) {
            permit.release();
            log.error("migration of '{}' failed unexpectedly", request.target(), e);
            failMigration(message, request.target(), Reason.SERVICE_FAILED, "the migration failed unexpectedly: " + e);
            return;
        }
        installed(result.target(), null);
        counters.migrated.increment();
        log.info("migrated '{}' to '{}' ({} held messages): prepare {} us, quiesce {} us, transfer {} us,"
                + " relocate {} us, gap {}", result.target(), result.toNode(), result.heldMessages(),
                result.prepareNs() / 1_000, result.quiesceNs() / 1_000, result.transferNs() / 1_000,
                result.relocateNs() / 1_000, result.gapNs() < 0 ? "unknown" : result.gapNs() / 1_000 + " us");
        permit.release();
        if (message.hasSender()) {
            context.reply(message, result);
        }
    }

    /** A step of a migration into this node, from its source's management service. */
    private void acceptStep(Message message, MigrationStep step) {
        String operation = "migration " + step.phase();
        if (refused(message, Operation.MIGRATE, operation, step.target())) {
            return;
        }
        if (step.phase() == MigrationStep.Phase.INSTALL) {
            // On the dispatcher, like an upgrade's swap: restore and registration are on the gap's
            // path, and the class was loaded off the dispatchers by PREPARE.
            try {
                replyBehindEverything(message, migrationTarget.install(step));
            } catch (LoadFailure e) {
                failMigration(message, step.target(), e.reason(), e.getMessage());
            } catch (RuntimeException e) {
                failMigration(message, step.target(), Reason.SERVICE_FAILED, operation + " failed: " + e);
            }
            return;
        }
        if (step.phase() == MigrationStep.Phase.HANDOVER) {
            // On the dispatcher: the hand-over is on the migration gap's path.
            try {
                migrationTarget.handover(step).whenComplete((done, error) -> {
                    if (error != null) {
                        failMigration(message, step.target(), Reason.SERVICE_FAILED, "hand-over failed: " + error);
                    } else {
                        counters.migratedIn.increment();
                        context.reply(message, done);
                    }
                });
            } catch (LoadFailure e) {
                failMigration(message, step.target(), e.reason(), e.getMessage());
            }
            return;
        }
        submit(steps, stepsIn, permit -> {
            MigrationStepDone done;
            try {
                done = migrationTarget.prepare(step);
            } catch (LoadFailure e) {
                permit.release();
                failMigration(message, step.target(), e.reason(), e.getMessage());
                return;
            } catch (RuntimeException e) {
                permit.release();
                failMigration(message, step.target(), Reason.SERVICE_FAILED, operation + " failed: " + e);
                return;
            }
            permit.release();
            context.reply(message, done);
        }, (reason, error) -> failMigration(message, step.target(), reason, error));
    }

    /**
     * The answer to an INSTALL, at the lowest criticality: the link's queue sends it after every
     * message queued before it for the source, among them those this node's senders sent to the
     * component before it was installed here. The source receives them, and forwards them back,
     * before it switches (see the package documentation). If a full queue sheds it, the source's
     * step times out and the component resumes there: nothing is lost.
     */
    private void replyBehindEverything(Message request, MigrationStepDone done) {
        if (request.hasSender()) {
            kernel.send(new Message(request.sender(), context.self(), kernel.clock().epochNanos(),
                    QoS.of(Criticality.NONE), done, kernel.newMessageId(), request.messageId()));
        }
    }

    private void failMigration(Message message, Profile target, Reason reason, String error) {
        counters.failed.increment();
        String operation = message.contents() instanceof MigrationStep step ? "migration " + step.phase() : MIGRATE;
        log.warn("{} request {} of '{}' failed ({}): {}", operation, message.messageId(), target, reason, error);
        reply(message, new ManagementFailure(operation, target, reason, error));
    }

    /** After a successful swap: the jar loader of the replaced logic is no longer needed. */
    private void installed(Profile profile, URLClassLoader newLoader) {
        URLClassLoader previous = newLoader == null ? jarLoaders.remove(profile) : jarLoaders.put(profile, newLoader);
        ImplementationLoader.closeQuietly(previous);
    }

    private void answer(Message message, Profile target, String oldImplementation, ImplementationLoader.Loaded loaded,
                        long loadNs, SwapTimings timings, long firstNs, long receivedNs) {
        long gapNs = firstNs == SwapTimings.UNKNOWN_NS || timings.lastOldHandlingEndNs() == SwapTimings.UNKNOWN_NS
                ? -1 : firstNs - timings.lastOldHandlingEndNs();
        long pauseNs = timings.pauseNs() == SwapTimings.UNKNOWN_NS ? -1 : timings.pauseNs();
        long totalNs = timings.swapEndNs() == SwapTimings.UNKNOWN_NS ? -1 : timings.swapEndNs() - receivedNs;
        var result = new UpgradeResult(target, oldImplementation, loaded.type().getName(), loaded.source(),
                timings.stateSchemaVersion(), loadNs, pauseNs, gapNs, totalNs);
        counters.upgraded.increment();
        log.info("upgraded '{}' from {} to {} ({}): load {} us, pause {} us, gap {}", target, oldImplementation,
                result.newImplementation(), result.source(), loadNs / 1_000, pauseNs / 1_000,
                gapNs < 0 ? "unknown" : gapNs / 1_000 + " us");
        reply(message, result);
    }

    private void fail(Message message, UpgradeRequest request, Reason reason, String error) {
        counters.failed.increment();
        log.warn("upgrade request {} of '{}' to {} failed ({}): {}", message.messageId(), request.target(),
                request.className(), reason, error);
        reply(message, new ManagementFailure(UPGRADE, request.target(), reason, error));
    }

    private void reply(Message request, ManagementFailure failure) {
        if (request.hasSender()) {
            context.reply(request, failure);
        }
    }

    private void reply(Message request, UpgradeResult result) {
        if (request.hasSender()) {
            context.reply(request, result);
        }
    }

    /**
     * Upgrades answered with a result. Any thread.
     *
     * @return the count so far (the instances that restarts make after {@link #install} share it)
     */
    public long upgradedCount() {
        return counters.upgraded.sum();
    }

    /**
     * Migrations of this node's components to other nodes answered with a result. Any thread.
     *
     * @return the count so far (the instances that restarts make after {@link #install} share it)
     */
    public long migratedCount() {
        return counters.migrated.sum();
    }

    /**
     * Migrated components that arrived at this node and were handed over. Any thread.
     *
     * @return the count so far (the instances that restarts make after {@link #install} share it)
     */
    public long migratedInCount() {
        return counters.migratedIn.sum();
    }

    /**
     * Upgrades and migrations (or their steps here) that failed, refusals on arrival not included;
     * a migration stopped inside by an access check (a step from another node than the one that
     * prepared it, an answer from another node than the target) counts here. Any thread.
     *
     * @return the count so far (the instances that restarts make after {@link #install} share it)
     */
    public long failedCount() {
        return counters.failed.sum();
    }

    /**
     * Requests and migration steps refused on arrival: from other nodes that the access list does
     * not allow (or relayed, or over an unauthenticated link), or of a kind the service does not
     * serve. Any thread.
     *
     * @return the count so far (the instances that restarts make after {@link #install} share it)
     */
    public long refusedCount() {
        return counters.refused.sum();
    }

    /**
     * Requests refused with {@link Reason#BUSY} because {@link ManagementConfig#maxQueuedOperations()}
     * were waiting (also counted in {@link #failedCount()}). Any thread.
     *
     * @return the count so far (the instances that restarts make after {@link #install} share it)
     */
    public long busyCount() {
        return counters.busy.sum();
    }

    /** The counters, shared by the instances that restarts make. */
    private static final class Counters {
        final LongAdder upgraded = new LongAdder();
        final LongAdder migrated = new LongAdder();
        final LongAdder migratedIn = new LongAdder();
        final LongAdder failed = new LongAdder();
        final LongAdder refused = new LongAdder();
        final LongAdder busy = new LongAdder();
    }
}
