package io.etherware.services.management;

import io.etherware.core.component.Component;
import io.etherware.core.component.ComponentContext;
import io.etherware.core.kernel.ComponentHost;
import io.etherware.core.kernel.EtherwareNode;
import io.etherware.core.message.Message;
import io.etherware.core.message.Profile;
import io.etherware.services.management.ManagementFailure.Reason;
import io.etherware.services.management.internal.AccessControl;
import io.etherware.services.management.internal.ImplementationLoader;
import io.etherware.services.management.internal.MigrationSource;
import io.etherware.services.management.internal.MigrationTarget;
import io.etherware.services.network.NetworkMessenger;
import java.util.Objects;
import java.util.Optional;
import java.util.concurrent.TimeUnit;
import java.util.concurrent.atomic.AtomicReference;
import org.slf4j.LoggerFactory;

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
 * operation at a time; the next wait in the same queue). From the hold to the hand-over (the gap)
 * the worker runs at the priority of the dispatcher the request's QoS is placed on, with the
 * node's {@code RealtimeScheduler} (SCHED_FIFO 80 for a HIGH request on Table II), as an upgrade's
 * swap does, and at its ordinary priority before and after. At the target, PREPARE (loading,
 * constructing) runs on a second thread of the service, with a queue of the same bound, and the
 * answers that wait for a first message are assembled there too: two nodes migrating components
 * to each other at once each serve the other's steps while their own migration waits; INSTALL
 * ({@code restore}, {@code onStart}, registration) and HANDOVER run on the service's dispatcher,
 * because they are on the migration gap's path. Migrating from this node needs the
 * {@link NetworkMessenger} given to {@link #install(EtherwareNode, ManagementConfig, NetworkMessenger)}.
 */
public final class ManagementService implements Component {

    // The parts, each given what it needs: Upgrades and Migrations serve the requests, sharing a
    // ManagementContext made at each start; two OperationQueues are the worker and the steps thread;
    // ManagementCounters and JarLoaders are shared by the instances that restarts make.

    private final ComponentHost kernel;
    private final ManagementConfig config;
    private final NetworkMessenger network;
    private final ImplementationLoader loader;
    private final AccessControl access;
    /** The jar class loader behind each component upgraded from a jar; closed when replaced. */
    private final JarLoaders jarLoaders;
    private final ManagementCounters counters;
    /** Upgrades' loading and migrations away from this node: one at a time, in arrival order. */
    private final OperationQueue worker;
    /** PREPARE steps of migrations into this node: apart, so two nodes migrating to each other go on. */
    private final OperationQueue steps;
    private ManagementContext running;
    private Upgrades upgrades;
    private Migrations migrations;

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
        this(kernel, config, network, new ManagementCounters(), new JarLoaders());
    }

    private ManagementService(ComponentHost kernel, ManagementConfig config, NetworkMessenger network,
                              ManagementCounters counters, JarLoaders jarLoaders) {
        this.kernel = Objects.requireNonNull(kernel, "kernel");
        this.config = Objects.requireNonNull(config, "config");
        Management.registerContents(kernel.contentsTypes());
        this.network = network;
        this.loader = new ImplementationLoader(config.allowlist(), config.trustedSigners(), config.classLoader(),
                kernel.contentsTypes());
        this.access = new AccessControl(kernel, config);
        this.counters = counters;
        this.jarLoaders = jarLoaders;
        this.worker = new OperationQueue("etherware-management-" + kernel.nodeId(), kernel.nodeId(), config,
                counters.busy);
        this.steps = new OperationQueue("etherware-management-steps-" + kernel.nodeId(), kernel.nodeId(), config,
                counters.busy);
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
        if (network != null && network.config().peerDownGraceNs() <= config.targetWatchNs()) {
            LoggerFactory.getLogger(ManagementService.class).warn("node {}: the network's peerDownGrace ({} ms) is not"
                    + " above two migration steps and the first-message wait ({} ms): a migration from this node whose"
                    + " target dies after the relocation leaves the component lost instead of resuming it here",
                    node.nodeId(), TimeUnit.NANOSECONDS.toMillis(network.config().peerDownGraceNs()),
                    TimeUnit.NANOSECONDS.toMillis(config.targetWatchNs()));
        }
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
        this.running = new ManagementContext(kernel, config, context, context.logger(), counters, access, jarLoaders);
        worker.start();
        steps.start();
        this.upgrades = new Upgrades(running, loader, worker);
        // The answers of steps into this node must not wait for this node's own migration away,
        // which may be waiting for the other node's answers.
        this.migrations = new Migrations(running, worker, steps, new MigrationSource(kernel, config, network, access),
                new MigrationTarget(kernel, config, loader, steps.continuations(), jarLoaders::installed,
                        counters.abandonedIn, counters.takenOverIn,
                        network == null ? node -> Optional.empty() : network::goneWithoutGoodbye));
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
            case UpgradeRequest request -> upgrades.accept(message, request);
            case MigrateRequest request -> migrations.accept(message, request);
            case MigrationStep step -> migrations.acceptStep(message, step);
            case Upgrades.Prepared prepared when context.self().equals(message.sender()) -> upgrades.swap(prepared);
            default -> {
                if (message.hasSender() && !message.isReply()) {
                    counters.refused.increment();
                    running.reply(message, new ManagementFailure(message.contents().getClass().getSimpleName(),
                            context.self(), Reason.BAD_REQUEST, "the management service does not serve "
                            + message.contents().getClass().getSimpleName() + " messages; send an UpgradeRequest"));
                } else {
                    running.log().debug("ignored {} ({})", message.messageId(), message.contents());
                }
            }
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
     * Migrations into this node that were begun here and given up, because their source did not
     * continue them in time: an instance prepared but never installed, or a component installed
     * but never handed over (see {@link ManagementConfig} for the waits). Nothing of them stays
     * registered. Any thread.
     *
     * @return the count so far (the instances that restarts make after {@link #install} share it)
     */
    public long abandonedInCount() {
        return counters.abandonedIn.sum();
    }

    /**
     * Migrations into this node completed here without their hand-over, because their source left
     * without a goodbye after sending the INSTALL and before it could have resumed the component
     * (its process ended: see {@link NetworkMessenger#goneWithoutGoodbye}), and did not come back
     * within a migration step's time: the component runs here with the state it handed over. Any
     * thread.
     *
     * @return the count so far (the instances that restarts make after {@link #install} share it)
     */
    public long takenOverInCount() {
        return counters.takenOverIn.sum();
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
}
