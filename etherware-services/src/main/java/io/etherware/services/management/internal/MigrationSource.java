package io.etherware.services.management.internal;

import io.etherware.core.component.ComponentState;
import io.etherware.core.component.RequestFailedException;
import io.etherware.core.component.Shell;
import io.etherware.core.kernel.ComponentHost;
import io.etherware.core.kernel.RemoteRoute;
import io.etherware.core.message.Message;
import io.etherware.core.message.Profile;
import io.etherware.core.message.QoS;
import io.etherware.services.management.Management;
import io.etherware.services.management.ManagementConfig;
import io.etherware.services.management.ManagementFailure;
import io.etherware.services.management.ManagementFailure.Reason;
import io.etherware.services.management.MigrateRequest;
import io.etherware.services.management.MigrationResult;
import io.etherware.services.management.MigrationStep;
import io.etherware.services.management.MigrationStep.Phase;
import io.etherware.services.management.MigrationStepDone;
import io.etherware.services.network.NetworkMessenger;
import java.time.Duration;
import java.util.concurrent.CompletableFuture;
import java.util.concurrent.ExecutionException;
import java.util.concurrent.TimeUnit;
import java.util.concurrent.TimeoutException;
import org.slf4j.Logger;
import org.slf4j.LoggerFactory;

/**
 * The source side of a migration: prepare at the target, hold at a message boundary, snapshot,
 * install at the target, relocate (forward the held messages), hand over. Any failure before the
 * relocation releases the hold, so the component resumes here with nothing lost; a target that
 * dies after the relocation, before it confirmed the hand-over, makes the component resume here
 * from the state it was handed ({@link ComponentHost#reinstate}). See the package documentation of
 * {@code io.etherware.services.management} for the ordering argument.
 *
 * <p>Threading: {@link #migrate} blocks for the target's answers, so it runs on the management
 * service's worker thread, never on a dispatcher; one migration at a time per service. From the
 * hold to the hand-over's answer that thread runs at the priority of the dispatcher that the
 * request's QoS gives it ({@link GapPriority}), as an upgrade's swap does, so that no step of the
 * gap waits for an ordinary thread's turn.
 */
public final class MigrationSource {

    private static final Logger log = LoggerFactory.getLogger(MigrationSource.class);
    /** The role of the profiles under which migrated components receive forwarded messages. */
    public static final String ARRIVAL_ROLE = "etherware.arrival";
    /** Beyond a request's own timeout, for the kernel's timer to fire it. */
    private static final long GRACE_NS = TimeUnit.SECONDS.toNanos(1);
    /** How often a target that left during a hand-over is looked at. */
    private static final long TARGET_WATCH_NS = TimeUnit.MILLISECONDS.toNanos(100);

    private final ComponentHost kernel;
    private final ManagementConfig config;
    private final NetworkMessenger network;
    private final AccessControl access;

    /**
     * @param network the node's messenger, for the route to the target and its clock; null on a
     *                node without one (its migrations are refused)
     * @param access  decides whether an answer really came from the target
     */
    public MigrationSource(ComponentHost kernel, ManagementConfig config, NetworkMessenger network,
                           AccessControl access) {
        this.kernel = kernel;
        this.config = config;
        this.network = network;
        this.access = access;
    }

    /**
     * Moves the component of {@code shell} as {@code request} asks. Worker thread.
     *
     * @param qos        the request's QoS: the gap runs at the priority of its dispatcher
     *                   ({@link GapPriority})
     * @param receivedNs when the request reached the management service
     * @throws LoadFailure if the migration failed; the component then runs here as before, unless
     *                     the failure says otherwise (a relocation that failed or did not switch)
     */
    public MigrationResult migrate(Shell shell, MigrateRequest request, QoS qos, long receivedNs) throws LoadFailure {
        String toNode = request.toNode();
        Profile profile = shell.profile();
        if (toNode.equals(kernel.nodeId())) {
            throw new LoadFailure(Reason.BAD_REQUEST, "toNode='" + toNode + "' is the node that hosts '" + profile
                    + "' already; name another node");
        }
        if (network == null) {
            throw new LoadFailure(Reason.BAD_REQUEST, "node '" + kernel.nodeId() + "' has no network: install its"
                    + " management service with ManagementService.install(node, config, networkMessenger)");
        }
        String className = request.className() != null ? request.className() : shell.logicType().getName();
        long stepNs = config.migrationStepTimeoutNs();
        // Unique to this migration: what the source forwards goes there, apart from the target's
        // own senders, which keep sending to the profile (through here) until the hand-over.
        Profile arrival = Profile.of(ARRIVAL_ROLE, "id", kernel.nodeId() + "-" + kernel.newMessageId().sequence());

        // (i) The target loads and constructs while the component still runs here.
        long prepareStartNs = kernel.clock().nanoTime();
        step(toNode, new MigrationStep(Phase.PREPARE, profile, kernel.nodeId(), arrival, className, request.jarPath(),
                request.configuration(), null, 0, stepNs), stepNs);
        long quiesceStartNs = kernel.clock().nanoTime();
        try (var raised = GapPriority.of(kernel, Management.profileOf(kernel.nodeId()), qos).raise()) {
            return moveHeld(shell, toNode, className, arrival, receivedNs, prepareStartNs, quiesceStartNs);
        }
    }

    /**
     * The migration gap, at the request's priority: holds the component here, ships its state,
     * relocates it and hands it over.
     */
    private MigrationResult moveHeld(Shell shell, String toNode, String className, Profile arrival,
                                     long receivedNs, long prepareStartNs, long quiesceStartNs) throws LoadFailure {
        Profile profile = shell.profile();
        long stepNs = config.migrationStepTimeoutNs();
        // (ii) Quiesce at a message boundary where the component waits for no reply (the outcomes
        // of its requests reach it here, where their callbacks are): from now on its messages are
        // kept here, in order.
        CompletableFuture<Void> held = kernel.holdAsync(profile, Duration.ofNanos(config.settleWaitNs()));
        long quiesceWaitNs = config.settleWaitNs() + stepNs;
        try {
            held.get(quiesceWaitNs, TimeUnit.NANOSECONDS);
        } catch (TimeoutException e) {
            held.thenRun(() -> kernel.release(profile)); // the hold lands later: undo it then
            throw new LoadFailure(Reason.NOT_RUNNING, "'" + profile + "' did not reach a message boundary within "
                    + TimeUnit.NANOSECONDS.toMillis(quiesceWaitNs) + " ms (a long handling?); it runs on at '"
                    + kernel.nodeId() + "'");
        } catch (InterruptedException e) {
            held.thenRun(() -> kernel.release(profile));
            Thread.currentThread().interrupt();
            throw new LoadFailure(Reason.SERVICE_FAILED, "interrupted while quiescing '" + profile + "'");
        } catch (ExecutionException e) {
            throw new LoadFailure(Reason.NOT_RUNNING, "'" + profile + "' could not be held: " + e.getCause());
        }
        long quiescedNs = kernel.clock().nanoTime();
        long quiescedEpochNs = kernel.clock().epochNanos();

        // (iii) The state travels as XML inside the install step; the target registers it, held.
        ComponentState state;
        try {
            state = kernel.snapshotAsync(profile).get(stepNs, TimeUnit.NANOSECONDS);
        } catch (ExecutionException | TimeoutException | InterruptedException e) {
            kernel.release(profile);
            if (e instanceof InterruptedException) {
                Thread.currentThread().interrupt();
            }
            Throwable cause = e instanceof ExecutionException ? e.getCause() : e;
            throw new LoadFailure(Reason.ROLLED_BACK, "the snapshot of '" + profile + "' failed (" + cause
                    + "); it resumed at '" + kernel.nodeId() + "'", cause);
        }
        long installSentNs = kernel.clock().nanoTime();
        try {
            step(toNode, new MigrationStep(Phase.INSTALL, profile, kernel.nodeId(), arrival, null, null, null, state, 0,
                    stepNs), stepNs);
        } catch (LoadFailure e) {
            kernel.release(profile);
            throw new LoadFailure(e.reason(), e.getMessage() + "; '" + profile + "' resumed at '" + kernel.nodeId()
                    + "'", e);
        }
        long installedNs = kernel.clock().nanoTime();

        // The switch: the profile now routes to the target, the held messages go first (FIFO stream).
        var route = new ArrivalRoute(network.routeTo(toNode), arrival, profile);
        try {
            awaitSwitch(kernel.relocateAsync(profile, route), profile, toNode, installSentNs);
        } catch (ExecutionException | InterruptedException e) {
            // The relocation failed (its profile was registered anew meanwhile, say): the component
            // may be stopped already; the release resumes it if it is not.
            try {
                kernel.release(profile);
            } catch (RuntimeException notHere) {
                log.debug("node {}: no release after the failed relocation of '{}': {}", kernel.nodeId(), profile,
                        notHere.toString());
            }
            if (e instanceof InterruptedException) {
                Thread.currentThread().interrupt();
            }
            throw new LoadFailure(Reason.SERVICE_FAILED, "relocating '" + profile + "' to '" + toNode + "' failed ("
                    + e + "); it may be stopped at '" + kernel.nodeId() + "' (see the log)", e);
        }
        long relocatedNs = kernel.clock().nanoTime();
        long heldMessages = route.forwardedSoFar();

        // Committed: the component lives at the target. The hand-over releases it there once the
        // messages sent to the arrival profile are in; from the seal on, they go to the profile,
        // and once the target's announcement is here, along the route that follows it.
        long forwarded = route.seal();
        network.followAnnouncements(profile, route, toNode);
        long firstEpochNs = -1;
        String implementation = className;
        long handoverTimeoutNs = stepNs + config.firstMessageWaitNs();
        long handoverSentNs = kernel.clock().nanoTime();
        try {
            MigrationStepDone done = step(toNode, new MigrationStep(Phase.HANDOVER, profile, kernel.nodeId(), arrival,
                    null, null, null, null, forwarded, stepNs), handoverTimeoutNs);
            firstEpochNs = done.firstHandlingEpochNs();
            implementation = done.implementation();
        } catch (LoadFailure e) {
            resumeIfTargetHasNone(shell, toNode, state, installSentNs, handoverSentNs + handoverTimeoutNs, e);
            log.warn("node {}: '{}' moved to '{}', but its hand-over was not confirmed: {}", kernel.nodeId(), profile,
                    toNode, e.getMessage());
        }
        long endNs = kernel.clock().nanoTime();
        long gapNs = firstEpochNs < 0 ? -1 : network.networkTime().toLocal(toNode, firstEpochNs) - quiescedEpochNs;
        return new MigrationResult(profile, kernel.nodeId(), toNode, implementation,
                state == null ? -1 : state.schemaVersion(), heldMessages, quiesceStartNs - prepareStartNs,
                quiescedNs - quiesceStartNs, installedNs - quiescedNs, relocatedNs - installedNs, gapNs,
                endNs - receivedNs);
    }

    /**
     * Waits for a relocation's switch. The relocation begins at once (the component is held, so at
     * a boundary): it stops the component here and forwards what the hold kept; the switch then
     * waits for the component's jobs already queued at a dispatcher to be forwarded as they come
     * up. Behind a long handling of another component on the same dispatcher that can take more
     * than a step; releasing the hold could not resume the component then, so this waits on: as
     * long as the target keeps its copy ({@link ManagementConfig#handoverWaitNs()} after the
     * INSTALL, less a step for the hand-over to reach it), the migration completes; later, the
     * hand-over finds the target's copy given up and the component resumes here from the state it
     * handed over ({@link #resumeIfTargetHasNone}), the messages forwarded meanwhile lost with that
     * copy. Waits at most twice the hand-over wait in all.
     *
     * @throws LoadFailure if the switch did not come by then: the component is lost (it is stopped
     *                     here, its copy at the target given up)
     */
    private void awaitSwitch(CompletableFuture<Void> switched, Profile profile, String toNode, long installSentNs)
            throws ExecutionException, InterruptedException, LoadFailure {
        long stepNs = config.migrationStepTimeoutNs();
        try {
            switched.get(stepNs, TimeUnit.NANOSECONDS);
            return;
        } catch (TimeoutException e) {
            log.warn("node {}: the relocation of '{}' has not switched after {} ms: jobs of it wait behind a long"
                    + " handling of another component on their dispatcher (a handler must not block); waiting on",
                    kernel.nodeId(), profile, TimeUnit.NANOSECONDS.toMillis(stepNs));
        }
        // The target's hand-over wait began after the INSTALL left here.
        long keptUntilNs = installSentNs + config.handoverWaitNs() - stepNs;
        try {
            switched.get(Math.max(0, keptUntilNs - kernel.clock().nanoTime()), TimeUnit.NANOSECONDS);
            return;
        } catch (TimeoutException e) {
            log.warn("node {}: the relocation of '{}' has still not switched; node '{}' gives its copy up, so it will"
                    + " resume here from the state it handed over once it switches", kernel.nodeId(), profile, toNode);
        }
        long lastNs = installSentNs + 2 * config.handoverWaitNs();
        try {
            switched.get(Math.max(0, lastNs - kernel.clock().nanoTime()), TimeUnit.NANOSECONDS);
        } catch (TimeoutException e) {
            String why = "the relocation of '" + profile + "' to '" + toNode + "' did not switch within "
                    + TimeUnit.NANOSECONDS.toMillis(2 * config.handoverWaitNs()) + " ms of the INSTALL: jobs of it"
                    + " waited behind a handling of another component on their dispatcher that ran longer (a"
                    + " handler must not block); '" + profile + "' is stopped at '" + kernel.nodeId()
                    + "' and its copy at '" + toNode + "' was given up: it is lost";
            log.error("node {}: {}", kernel.nodeId(), why);
            throw new LoadFailure(Reason.SERVICE_FAILED, why, e);
        }
    }

    /**
     * After a hand-over that was not confirmed, resumes the component here from the state it
     * handed over when the target holds no copy that could run:
     * <ul>
     *   <li>the target answered that nothing of it is there ({@code UNKNOWN_COMPONENT}: it gave its
     *       copy up after its hand-over wait, the relocation having been slow); or</li>
     *   <li>its process left without a goodbye after the INSTALL was sent and before this side
     *       stopped waiting for the hand-over's answer, and stays away for a step's time (the
     *       condition of a take-over, {@code MigrationTarget}, the other way round): it died before
     *       its answer came, having run the component at most for the messages handled before
     *       that answer would have left.</li>
     * </ul>
     * Otherwise returns, and the component stays with the target (one that answered late runs it).
     *
     * @param sinceNs  when the INSTALL was sent: a departure before it was of another incarnation
     * @param untilNs  when this side stopped waiting for the hand-over's answer: a target that left
     *                 later may have answered late and run the component for long
     * @param handOver why the hand-over failed
     * @throws LoadFailure if the component resumed here, or should have and could not
     */
    private void resumeIfTargetHasNone(Shell relocated, String toNode, ComponentState state, long sinceNs,
                                       long untilNs, LoadFailure handOver) throws LoadFailure {
        String why;
        Reason reason = Reason.TARGET_UNREACHABLE;
        if (handOver.reason() == Reason.UNKNOWN_COMPONENT) {
            why = handOver.getMessage();
            reason = Reason.ROLLED_BACK;
        } else if (targetLeft(toNode, sinceNs, untilNs, relocated.profile())) {
            why = handOver.getMessage() + "; node '" + toNode + "' left without a goodbye after the INSTALL and has"
                    + " not come back for " + TimeUnit.NANOSECONDS.toMillis(config.migrationStepTimeoutNs()) + " ms";
        } else {
            return;
        }
        Profile profile = relocated.profile();
        Shell back;
        try {
            back = kernel.reinstate(relocated, state);
        } catch (Exception | LinkageError e) {
            log.error("node {}: '{}' could not resume from the state it handed over ({}): {}", kernel.nodeId(),
                    profile, why, e.toString());
            throw new LoadFailure(Reason.SERVICE_FAILED, why + "; resuming '" + profile + "' at '" + kernel.nodeId()
                    + "' from the state it handed over failed: " + e, e);
        }
        if (back.state() == Shell.State.FAILED) {
            throw new LoadFailure(Reason.ROLLED_BACK, why + "; '" + profile + "' was brought back at '"
                    + kernel.nodeId() + "' from the state it handed over, but its onStart threw (see the log)");
        }
        log.warn("node {}: {}; '{}' resumed here from the state it handed over (what was sent to it since the"
                + " relocation went to that node and is lost)", kernel.nodeId(), why, profile);
        throw new LoadFailure(reason, why + "; '" + profile + "' resumed at '" + kernel.nodeId()
                + "' from the state it handed over", handOver);
    }

    /**
     * Whether node {@code toNode}'s process left without a goodbye within ({@code sinceNs},
     * {@code untilNs}] and stays away for a step's time; looks for up to two steps.
     */
    private boolean targetLeft(String toNode, long sinceNs, long untilNs, Profile profile) throws LoadFailure {
        long stepNs = config.migrationStepTimeoutNs();
        long lookUntilNs = kernel.clock().nanoTime() + 2 * stepNs;
        try {
            while (true) {
                long nowNs = kernel.clock().nanoTime();
                long goneNs = network.goneWithoutGoodbye(toNode).map(Duration::toNanos).orElse(-1L);
                long leftAtNs = nowNs - goneNs;
                if (goneNs >= 0 && leftAtNs > sinceNs && leftAtNs <= untilNs) {
                    if (goneNs >= stepNs) {
                        return true;
                    }
                } else if (nowNs >= lookUntilNs) {
                    return false;
                }
                Thread.sleep(TimeUnit.NANOSECONDS.toMillis(TARGET_WATCH_NS));
            }
        } catch (InterruptedException e) {
            Thread.currentThread().interrupt();
            throw new LoadFailure(Reason.SERVICE_FAILED, "interrupted while looking whether node '" + toNode
                    + "', which did not confirm the hand-over of '" + profile + "', is gone");
        }
    }

    /** Sends one step to the target's management service and waits for its answer. */
    private MigrationStepDone step(String toNode, MigrationStep step, long timeoutNs) throws LoadFailure {
        var message = new Message(Management.profileOf(toNode), kernel.profile(), kernel.clock().epochNanos(),
                Management.REQUEST_QOS, step, kernel.newMessageId(), null);
        Message reply;
        try {
            reply = kernel.request(message, timeoutNs).get(timeoutNs + GRACE_NS, TimeUnit.NANOSECONDS);
        } catch (ExecutionException e) {
            String why = e.getCause() instanceof RequestFailedException failed ? failed.getMessage()
                    : String.valueOf(e.getCause());
            throw new LoadFailure(Reason.TARGET_UNREACHABLE, "node '" + toNode + "' did not answer the "
                    + step.phase() + " step: " + why, e.getCause());
        } catch (TimeoutException e) {
            throw new LoadFailure(Reason.TARGET_UNREACHABLE, "node '" + toNode + "' did not answer the "
                    + step.phase() + " step within " + TimeUnit.NANOSECONDS.toMillis(timeoutNs) + " ms");
        } catch (InterruptedException e) {
            Thread.currentThread().interrupt();
            throw new LoadFailure(Reason.SERVICE_FAILED, "interrupted during the " + step.phase() + " step");
        }
        // Taken from the connection, not from the answer's text: another node that learned the
        // step's id must not be able to answer for the target.
        String refusal = access.answerRefusal(reply, toNode, step);
        if (refusal != null) {
            log.warn("node {}: refused an answer ({}) to the {} step of '{}': {}", kernel.nodeId(), reply.messageId(),
                    step.phase(), step.target(), refusal);
            throw new LoadFailure(Reason.REMOTE_REFUSED, refusal);
        }
        return switch (reply.contents()) {
            case MigrationStepDone done -> done;
            case ManagementFailure failure -> throw new LoadFailure(failure.reason(), "node '" + toNode + "' failed the "
                    + step.phase() + " step: " + failure.error());
            default -> throw new LoadFailure(Reason.SERVICE_FAILED, "node '" + toNode + "' answered the "
                    + step.phase() + " step with " + reply.contents().getClass().getSimpleName());
        };
    }

    /**
     * The route to the target for the moved profile. Until {@link #seal} each message goes to the
     * arrival profile there (so it is kept with the held ones, ahead of what the target's own
     * senders send), counted; from then on to the profile itself. The count at the seal is the
     * hand-over's: once that many have arrived, the target admits the component and drops the
     * arrival profile, which nothing addresses any more.
     *
     * <p>Thread-safety: any sender; before the seal, deliveries are serialized with it.
     */
    private static final class ArrivalRoute implements RemoteRoute {
        private final RemoteRoute to;
        private final Profile arrival;
        private final Profile profile;
        private volatile boolean sealed;
        private long forwarded; // guarded by this

        ArrivalRoute(RemoteRoute to, Profile arrival, Profile profile) {
            this.to = to;
            this.arrival = arrival;
            this.profile = profile;
        }

        @Override
        public void deliver(Message message) {
            if (!sealed) {
                synchronized (this) {
                    if (!sealed) {
                        to.deliver(message.withProfile(arrival));
                        forwarded++;
                        return;
                    }
                }
            }
            // The exact profile: a query that resolved to it here might not resolve alike there.
            to.deliver(message.profile().equals(profile) ? message : message.withProfile(profile));
        }

        /** Ends the forwarding to the arrival profile; returns how many messages went there. */
        synchronized long seal() {
            sealed = true;
            return forwarded;
        }

        synchronized long forwardedSoFar() {
            return forwarded;
        }

        @Override
        public boolean isServedBy(String nodeId) {
            return to.isServedBy(nodeId);
        }

        @Override
        public String toString() {
            return to.toString();
        }
    }
}
