package io.etherware.services.management;

import io.etherware.core.component.ComponentContext;
import io.etherware.core.kernel.Kernel;
import io.etherware.core.message.ContentsTypes;
import io.etherware.core.message.Criticality;
import io.etherware.core.message.Message;
import io.etherware.core.message.Profile;
import io.etherware.core.message.QoS;
import java.time.Duration;
import java.util.Objects;
import java.util.concurrent.CompletableFuture;

/**
 * The client of the management services: asks a node to upgrade one of its components, or to
 * migrate one to another node, and returns the outcome with its timings.
 *
 * <pre>{@code
 * UpgradeResult result = Management.upgrade(node, "plant-1", Profile.parse("controller[car=1]"),
 *         Implementation.ofClass("com.example.ControllerV2")).join();
 * log.info("swapped in {} us", result.gapNs() / 1_000);
 *
 * MigrationResult moved = Management.migrate(node, "node-2", Profile.parse("controller[car=1]"), "node-1").join();
 * log.info("migration gap {} us", moved.gapNs() / 1_000);
 * }</pre>
 *
 * <p>Requests travel as messages at {@link Criticality#HIGH} (paper Section VI-C1: the upgrade
 * request has high criticality so the upgrade runs at the highest priority) to
 * {@link #profileOf(String) the node's management service}, so a node reachable through a network
 * route is managed the same way as the local one, if its access list lets the requesting node ask
 * (see {@link ManagementConfig}).
 *
 * <p>Thread-safety: stateless; every method may be called from any thread. The futures never
 * block; see {@link Kernel#request} and {@link ComponentContext#request} for the thread that
 * completes them.
 */
public final class Management {

    /** The role of the management service: its profile is {@code etherware.management[node=<id>]}. */
    public static final String ROLE = "etherware.management";
    /** The timeout of a request made without one: beyond an upgrade's default wait for its first message. */
    public static final Duration DEFAULT_TIMEOUT = Duration.ofSeconds(10);
    /** The QoS of management requests. */
    public static final QoS REQUEST_QOS = QoS.of(Criticality.HIGH);

    private Management() {
    }

    /**
     * The profile of the management service of node {@code nodeId}.
     *
     * @param nodeId the node's id
     * @return {@code etherware.management[node=<nodeId>]}
     */
    public static Profile profileOf(String nodeId) {
        return Profile.of(ROLE, "node", nodeId);
    }

    /**
     * Registers the management contents ({@code etherware.upgrade}, {@code etherware.upgradeResult},
     * {@code etherware.managementFailure}, {@code etherware.migrate}, {@code etherware.migrationResult},
     * {@code etherware.migrationStep}, {@code etherware.migrationStepDone}) in {@code types}. A
     * {@link ManagementService} does this for its node, and so do the methods here that take a
     * {@link Kernel}; a node whose components ask another node's service (the forms taking a
     * {@link ComponentContext}) calls it for its own registry ({@code node.contentsTypes()}).
     * Idempotent.
     *
     * @param types the registry to add the management types to
     * @throws IllegalArgumentException if {@code types} already has one of those names or records
     *                                  under another partner
     */
    public static void registerContents(ContentsTypes types) {
        types.register("etherware.upgrade", UpgradeRequest.class);
        types.register("etherware.upgradeResult", UpgradeResult.class);
        types.register("etherware.managementFailure", ManagementFailure.class);
        types.register("etherware.migrate", MigrateRequest.class);
        types.register("etherware.migrationResult", MigrationResult.class);
        types.register("etherware.migrationStep", MigrationStep.class);
        types.register("etherware.migrationStepDone", MigrationStepDone.class);
    }

    /**
     * {@link #upgrade(Kernel, String, Profile, Implementation, Duration)} with {@link #DEFAULT_TIMEOUT}.
     *
     * @param kernel         the requesting node; its node profile is the sender
     * @param nodeId         the id of the node that hosts the component (this node's, or another
     *                       reachable through a network route)
     * @param target         the component's profile on that node, exact or a query matching one
     * @param implementation the new logic
     * @return the outcome; fails with {@link ManagementException} when the node refused or the
     *         upgrade failed (the old logic then serves on), or with
     *         {@link io.etherware.core.component.RequestFailedException} when no answer came
     */
    public static CompletableFuture<UpgradeResult> upgrade(Kernel kernel, String nodeId, Profile target,
                                                           Implementation implementation) {
        return upgrade(kernel, nodeId, target, implementation, DEFAULT_TIMEOUT);
    }

    /**
     * Asks node {@code nodeId} to replace the logic of its component {@code target} with
     * {@code implementation}, from outside any component ({@code kernel}'s node profile is the
     * sender). The future completes on a kernel thread; see {@link Kernel#request}.
     *
     * @param kernel         the requesting node; its node profile is the sender
     * @param nodeId         the id of the node that hosts the component (this node's, or another
     *                       reachable through a network route)
     * @param target         the component's profile on that node, exact or a query matching one
     * @param implementation the new logic
     * @param timeout        how long to wait for the answer; &gt; 0, and longer than the node's
     *                       {@link ManagementConfig#firstMessageWaitNs()} plus the loading
     * @return the outcome; fails with {@link ManagementException} when the node refused or the
     *         upgrade failed (the old logic then serves on), or with
     *         {@link io.etherware.core.component.RequestFailedException} when no answer came
     */
    public static CompletableFuture<UpgradeResult> upgrade(Kernel kernel, String nodeId, Profile target,
                                                           Implementation implementation, Duration timeout) {
        Objects.requireNonNull(kernel, "kernel");
        registerContents(kernel.contentsTypes());
        var request = new Message(profileOf(nodeId), kernel.profile(), kernel.clock().epochNanos(), REQUEST_QOS,
                UpgradeRequest.of(target, implementation), kernel.newMessageId(), null);
        return kernel.request(request, timeout.toNanos()).thenApply(Management::upgradeResultOf);
    }

    /**
     * {@link #upgrade(ComponentContext, String, Profile, Implementation, Duration)} with
     * {@link #DEFAULT_TIMEOUT}. Never wait for the future on a dispatcher.
     *
     * @param context        the requesting component's context; the component is the sender
     * @param nodeId         the id of the node that hosts the component
     * @param target         the component's profile on that node, exact or a query matching one
     * @param implementation the new logic
     * @return the outcome; fails with {@link ManagementException} when the node refused or the
     *         upgrade failed (the old logic then serves on), or with
     *         {@link io.etherware.core.component.RequestFailedException} when no answer came
     */
    public static CompletableFuture<UpgradeResult> upgrade(ComponentContext context, String nodeId, Profile target,
                                                           Implementation implementation) {
        return upgrade(context, nodeId, target, implementation, DEFAULT_TIMEOUT);
    }

    /**
     * From a component (the paper's Requester): asks node {@code nodeId} to upgrade {@code target}.
     * The future completes on the requesting component's dispatcher, like any
     * {@link ComponentContext#request}; never wait for it there.
     *
     * @param context        the requesting component's context; the component is the sender
     * @param nodeId         the id of the node that hosts the component
     * @param target         the component's profile on that node, exact or a query matching one
     * @param implementation the new logic
     * @param timeout        how long to wait for the answer; &gt; 0, and longer than the node's
     *                       {@link ManagementConfig#firstMessageWaitNs()} plus the loading
     * @return the outcome; fails with {@link ManagementException} when the node refused or the
     *         upgrade failed (the old logic then serves on), or with
     *         {@link io.etherware.core.component.RequestFailedException} when no answer came
     */
    public static CompletableFuture<UpgradeResult> upgrade(ComponentContext context, String nodeId, Profile target,
                                                           Implementation implementation, Duration timeout) {
        Objects.requireNonNull(context, "context");
        return context.request(profileOf(nodeId), UpgradeRequest.of(target, implementation), REQUEST_QOS,
                timeout.toNanos()).thenApply(Management::upgradeResultOf);
    }

    /**
     * {@link #migrate(Kernel, String, Profile, String, Duration)} with {@link #DEFAULT_TIMEOUT}.
     *
     * @param kernel   the requesting node; its node profile is the sender
     * @param fromNode the id of the node that hosts the component now
     * @param target   the component's profile there, exact or a query matching one
     * @param toNode   the id of the node to move it to
     * @return the outcome with its phase timings and gap; fails with {@link ManagementException}
     *         when a node refused or the migration failed (the component then runs on at
     *         {@code fromNode}, nothing lost), or with
     *         {@link io.etherware.core.component.RequestFailedException} when no answer came
     */
    public static CompletableFuture<MigrationResult> migrate(Kernel kernel, String fromNode, Profile target,
                                                             String toNode) {
        return migrate(kernel, fromNode, MigrateRequest.of(target, toNode), DEFAULT_TIMEOUT);
    }

    /**
     * Asks node {@code fromNode} to move its component {@code target} to node {@code toNode}, as
     * an instance of the class it runs now (constructed there with its no-arg constructor), from
     * outside any component ({@code kernel}'s node profile is the sender). The future completes
     * on a kernel thread; see {@link Kernel#request}.
     *
     * @param kernel   the requesting node
     * @param fromNode the id of the node that hosts the component now
     * @param target   the component's profile there, exact or a query matching one
     * @param toNode   the id of the node to move it to
     * @param timeout  how long to wait for the answer, &gt; 0: longer than the source's
     *                 {@link ManagementConfig#migrationStepTimeoutNs()} times the three steps
     * @return the outcome with its phase timings and gap; fails with {@link ManagementException}
     *         when a node refused or the migration failed (the component then runs on at
     *         {@code fromNode}, nothing lost), or with
     *         {@link io.etherware.core.component.RequestFailedException} when no answer came
     */
    public static CompletableFuture<MigrationResult> migrate(Kernel kernel, String fromNode, Profile target,
                                                             String toNode, Duration timeout) {
        return migrate(kernel, fromNode, MigrateRequest.of(target, toNode), timeout);
    }

    /**
     * Sends {@code request} (e.g. {@link MigrateRequest#of(Profile, String, Implementation)} for
     * another class or a configured constructor) to node {@code fromNode}, from outside any
     * component. The future completes on a kernel thread; see {@link Kernel#request}.
     *
     * @param kernel   the requesting node; its node profile is the sender
     * @param fromNode the id of the node that hosts the component now
     * @param request  what to move where, and as which class
     * @param timeout  how long to wait for the answer, &gt; 0: longer than the source's
     *                 {@link ManagementConfig#migrationStepTimeoutNs()} times the three steps
     * @return the outcome with its phase timings and gap; fails with {@link ManagementException}
     *         when a node refused or the migration failed (the component then runs on at
     *         {@code fromNode}, nothing lost), or with
     *         {@link io.etherware.core.component.RequestFailedException} when no answer came
     */
    public static CompletableFuture<MigrationResult> migrate(Kernel kernel, String fromNode, MigrateRequest request,
                                                             Duration timeout) {
        Objects.requireNonNull(kernel, "kernel");
        registerContents(kernel.contentsTypes());
        var message = new Message(profileOf(fromNode), kernel.profile(), kernel.clock().epochNanos(), REQUEST_QOS,
                request, kernel.newMessageId(), null);
        return kernel.request(message, timeout.toNanos()).thenApply(Management::migrationResultOf);
    }

    /**
     * From a component (the paper's Requester, Section VI-C2): asks node {@code fromNode} to move
     * {@code target} to node {@code toNode}. The future completes on the requesting component's
     * dispatcher, like any {@link ComponentContext#request}; never wait for it there.
     *
     * @param context  the requesting component's context; the component is the sender
     * @param fromNode the id of the node that hosts the component now
     * @param request  what to move where, and as which class
     * @param timeout  how long to wait for the answer, &gt; 0: longer than the source's
     *                 {@link ManagementConfig#migrationStepTimeoutNs()} times the three steps
     * @return the outcome with its phase timings and gap; fails with {@link ManagementException}
     *         when a node refused or the migration failed (the component then runs on at
     *         {@code fromNode}, nothing lost), or with
     *         {@link io.etherware.core.component.RequestFailedException} when no answer came
     */
    public static CompletableFuture<MigrationResult> migrate(ComponentContext context, String fromNode,
                                                             MigrateRequest request, Duration timeout) {
        Objects.requireNonNull(context, "context");
        return context.request(profileOf(fromNode), request, REQUEST_QOS, timeout.toNanos())
                .thenApply(Management::migrationResultOf);
    }

    /**
     * The result an answer to a migration request carries, for callers that send the request
     * themselves.
     *
     * @param reply the answer
     * @return its {@link MigrationResult}
     * @throws ManagementException   if the answer is a {@link ManagementFailure}
     * @throws IllegalStateException if the answer is anything else
     */
    public static MigrationResult migrationResultOf(Message reply) {
        return switch (reply.contents()) {
            case MigrationResult result -> result;
            case ManagementFailure failure -> throw new ManagementException(failure);
            default -> throw new IllegalStateException("the answer " + reply.messageId() + " to a migration carries "
                    + reply.contents().getClass().getSimpleName() + ", not a migration result");
        };
    }

    /**
     * The result an answer to an upgrade request carries, for callers that send the request
     * themselves.
     *
     * @param reply the answer
     * @return its {@link UpgradeResult}
     * @throws ManagementException   if the answer is a {@link ManagementFailure}
     * @throws IllegalStateException if the answer is anything else
     */
    public static UpgradeResult upgradeResultOf(Message reply) {
        return switch (reply.contents()) {
            case UpgradeResult result -> result;
            case ManagementFailure failure -> throw new ManagementException(failure);
            default -> throw new IllegalStateException("the answer " + reply.messageId() + " to an upgrade carries "
                    + reply.contents().getClass().getSimpleName() + ", not an upgrade result");
        };
    }
}
