package io.etherware.services.management.internal;

import io.etherware.core.component.Component;
import io.etherware.core.component.Shell;
import io.etherware.core.kernel.ComponentHost;
import io.etherware.core.kernel.Endpoint;
import io.etherware.core.kernel.ProfileResolutionException;
import io.etherware.core.message.Profile;
import io.etherware.services.management.ManagementConfig;
import io.etherware.services.management.ManagementFailure.Reason;
import io.etherware.services.management.MigrationStep;
import io.etherware.services.management.MigrationStep.Phase;
import io.etherware.services.management.MigrationStepDone;
import java.net.URLClassLoader;
import java.time.Duration;
import java.util.Map;
import java.util.Optional;
import java.util.concurrent.CompletableFuture;
import java.util.concurrent.ConcurrentHashMap;
import java.util.concurrent.Executor;
import java.util.concurrent.TimeUnit;
import java.util.concurrent.atomic.AtomicReference;
import java.util.concurrent.atomic.LongAdder;
import java.util.function.BiConsumer;
import java.util.function.Function;
import java.util.function.Supplier;
import org.slf4j.Logger;
import org.slf4j.LoggerFactory;

/**
 * The target side of a migration: {@link Phase#PREPARE} loads and constructs the new instance,
 * {@link Phase#INSTALL} restores the shipped state into it and registers it <em>held</em> under the
 * migration's arrival profile ({@link ComponentHost#addHeld}), {@link Phase#HANDOVER} admits it under its
 * own profile and releases it ({@link ComponentHost#admit}) once the source has forwarded the messages it
 * held. A component installed whose source's process left without a goodbye before the source
 * could have resumed it (its INSTALL step failing), and stayed away for a migration step's time, is
 * taken over: admitted with what was forwarded, since that source resumed nothing. One installed
 * but otherwise never handed over within
 * {@link ManagementConfig#handoverWaitNs()} is removed again: its source has resumed it by then,
 * or resumes it when its late HANDOVER is answered that nothing of it is here
 * ({@code UNKNOWN_COMPONENT}).
 * An instance prepared but never installed is discarded after
 * {@code settleWait + 2 × migrationStepTimeout + handoverWait}: by then its source has sent the
 * INSTALL (it waits at most {@code settleWait} and a step for the hold, then a step for the
 * snapshot), or resumed the component, or died; the hand-over wait is the margin for a late
 * step. Either way the migration counts as abandoned
 * ({@link io.etherware.services.management.ManagementService#abandonedInCount()}), and nothing of
 * it stays here.
 *
 * <p>Threading: {@link #prepare} loads code and runs constructors, so it runs on the management
 * service's thread for steps into this node (not its worker, which may be busy with a migration
 * away that waits for the other node). {@link #install} runs the component's {@code restore} and {@code onStart}
 * (which should be quick, as in an upgrade) and {@link #handover} is quick: both run on the
 * service's dispatcher, because they are on the migration gap's path.
 */
public final class MigrationTarget {

    private static final Logger log = LoggerFactory.getLogger(MigrationTarget.class);
    /** How often an installed component's source is looked at until its hand-over. */
    private static final long SOURCE_WATCH_NS = TimeUnit.MILLISECONDS.toNanos(100);
    /** Allowed for the error of the source's INSTALL time stamp, as NetworkTime translated it. */
    private static final long CLOCK_MARGIN_NS = TimeUnit.MILLISECONDS.toNanos(50);

    /** A prepared instance, bound to the node whose PREPARE made it. */
    private record Prepared(String fromNode, ImplementationLoader.Loaded loaded, Component instance, long loadNs) {
    }

    /**
     * An installed component, bound to the node whose migration it is.
     *
     * @param mayResumeAtNs from when (this node's {@code nanoTime}) its source may have resumed it,
     *                      its INSTALL step failed: the step's sending plus the source's step timeout,
     *                      less {@link #CLOCK_MARGIN_NS}
     */
    private record Arrived(String fromNode, Profile arrival, ImplementationLoader.Loaded loaded,
                           CompletableFuture<Long> firstHandlingNs, long mayResumeAtNs) {
    }

    private final ComponentHost kernel;
    private final ManagementConfig config;
    private final ImplementationLoader loader;
    private final Executor continuations;
    /** Told of the jar loader (or null) behind a component that now runs here. */
    private final BiConsumer<Profile, URLClassLoader> installed;
    /** Counts the migrations into this node given up here (prepared or installed, never handed over). */
    private final LongAdder abandoned;
    /** Counts the installed components taken over here because their source left without a goodbye. */
    private final LongAdder takenOver;
    /** How long ago a node's process left without a goodbye, if it did. */
    private final Function<String, Optional<Duration>> sourceGone;
    private final Map<Profile, Prepared> prepared = new ConcurrentHashMap<>();
    private final Map<Profile, Arrived> arrived = new ConcurrentHashMap<>();

    /**
     * @param continuations where answers that wait are assembled (the service's steps thread)
     * @param installed     told when a migrated component is handed over, with its jar loader
     * @param abandoned     counts the migrations given up here
     * @param takenOver     counts the installed components taken over because their source left
     * @param sourceGone    how long ago a node's process left without a goodbye, if it did (see
     *                      {@code NetworkMessenger.goneWithoutGoodbye})
     */
    public MigrationTarget(ComponentHost kernel, ManagementConfig config, ImplementationLoader loader,
                           Executor continuations, BiConsumer<Profile, URLClassLoader> installed,
                           LongAdder abandoned, LongAdder takenOver, Function<String, Optional<Duration>> sourceGone) {
        this.kernel = kernel;
        this.config = config;
        this.loader = loader;
        this.continuations = continuations;
        this.installed = installed;
        this.abandoned = abandoned;
        this.takenOver = takenOver;
        this.sourceGone = sourceGone;
    }

    /**
     * How long a source must have been gone, without a goodbye, before an installed component is
     * taken over: a migration step's time, many redial delays, so that a live source whose
     * connection was only reset is back by then.
     */
    static long sourceGoneAfterNs(ManagementConfig config) {
        return config.migrationStepTimeoutNs();
    }

    /**
     * How long a prepared instance waits for its INSTALL: as long as its source may wait for the
     * hold and the snapshot, plus the hand-over wait as the margin for a late step.
     */
    static long preparedKeepNs(ManagementConfig config) {
        return config.settleWaitNs() + 2 * config.migrationStepTimeoutNs() + config.handoverWaitNs();
    }

    /** Steps thread: loads the class and constructs the instance; a later prepare of the profile replaces it. */
    public MigrationStepDone prepare(MigrationStep step) throws LoadFailure {
        Profile profile = step.target();
        if (hostsLocally(profile)) {
            throw new LoadFailure(Reason.BAD_REQUEST, "node '" + kernel.nodeId() + "' hosts '" + profile
                    + "' already; a profile names one component");
        }
        if (step.className() == null) {
            throw new LoadFailure(Reason.BAD_REQUEST, "the PREPARE step of '" + profile + "' names no class");
        }
        long startNs = kernel.clock().nanoTime();
        ImplementationLoader.Loaded loaded;
        try {
            loaded = loader.load(step.className(), step.jarPath(), step.configuration());
        } catch (RuntimeException | LinkageError e) {
            throw new LoadFailure(Reason.CLASS_NOT_LOADABLE, "loading '" + step.className() + "' failed: " + e, e);
        }
        Component instance = loaded.factory().get();
        long loadNs = kernel.clock().nanoTime() - startNs;
        var ready = new Prepared(step.fromNode(), loaded, instance, loadNs);
        Prepared previous = prepared.put(profile, ready);
        if (previous != null) {
            previous.loaded().discard();
        }
        CompletableFuture.delayedExecutor(preparedKeepNs(config), TimeUnit.NANOSECONDS)
                .execute(() -> forgetPrepared(profile, ready));
        return new MigrationStepDone(Phase.PREPARE, profile, loaded.type().getName(), loadNs, -1);
    }

    /**
     * Dispatcher: restores the state into the prepared instance and registers it, held.
     *
     * @param sentEpochNs when the source sent the step, in this node's epoch clock (its time stamp,
     *                    as NetworkTime translated it)
     */
    public MigrationStepDone install(MigrationStep step, long sentEpochNs) throws LoadFailure {
        Profile profile = step.target();
        Prepared ready = prepared.get(profile);
        if (ready == null) {
            throw new LoadFailure(Reason.BAD_REQUEST, "'" + profile + "' was not prepared on node '" + kernel.nodeId()
                    + "', or its preparation was discarded after " + TimeUnit.NANOSECONDS.toMillis(preparedKeepNs(config))
                    + " ms without an INSTALL; send PREPARE first");
        }
        requireSameSource(step, ready.fromNode());
        if (!prepared.remove(profile, ready)) {
            throw new LoadFailure(Reason.BAD_REQUEST, "the preparation of '" + profile + "' on node '" + kernel.nodeId()
                    + "' was replaced meanwhile; send PREPARE again");
        }
        long startNs = kernel.clock().nanoTime();
        long sentNs = startNs - Math.max(0, kernel.clock().epochNanos() - sentEpochNs);
        // A source that does not say its step timeout is taken to share this node's.
        long sourceStepNs = step.stepTimeoutNs() > 0 ? step.stepTimeoutNs() : config.migrationStepTimeoutNs();
        String type = ready.loaded().type().getName();
        try {
            if (step.state() != null) {
                ready.instance().restore(step.state());
            }
        } catch (Throwable e) {
            ready.loaded().discard();
            throw new LoadFailure(Reason.ROLLED_BACK, "restore of " + type + " threw " + e, e);
        }
        var first = new AtomicReference<>(ready.instance());
        Supplier<Component> factory = () -> {
            Component unused = first.getAndSet(null);
            return unused != null ? unused : ready.loaded().factory().get();
        };
        var firstHandlingNs = new CompletableFuture<Long>();
        Shell shell;
        try {
            shell = kernel.addHeld(profile, step.arrival(), factory, firstHandlingNs::complete);
        } catch (RuntimeException e) {
            ready.loaded().discard();
            throw new LoadFailure(Reason.BAD_REQUEST, "'" + profile + "' cannot be registered on node '"
                    + kernel.nodeId() + "': " + e.getMessage(), e);
        }
        if (shell.state() != Shell.State.RUNNING) {
            kernel.removeAsync(step.arrival());
            ready.loaded().discard();
            throw new LoadFailure(Reason.ROLLED_BACK, "onStart of " + type + " threw (see the log); it was removed");
        }
        var arrival = new Arrived(step.fromNode(), step.arrival(), ready.loaded(), firstHandlingNs,
                sentNs + sourceStepNs - CLOCK_MARGIN_NS);
        arrived.put(profile, arrival);
        CompletableFuture.delayedExecutor(config.handoverWaitNs(), TimeUnit.NANOSECONDS)
                .execute(() -> giveUp(profile, arrival));
        watchSource(profile, arrival);
        return new MigrationStepDone(Phase.INSTALL, profile, type, kernel.clock().nanoTime() - startNs, -1);
    }

    /**
     * Dispatcher: releases the arrived component. The answer completes once its first message
     * began, or after {@link ManagementConfig#firstMessageWaitNs()} without the gap.
     */
    public CompletableFuture<MigrationStepDone> handover(MigrationStep step) throws LoadFailure {
        Profile profile = step.target();
        Arrived arrival = arrived.get(profile);
        if (arrival != null) {
            requireSameSource(step, arrival.fromNode());
        }
        if (arrival == null || !arrived.remove(profile, arrival)) {
            if (hostsLocally(profile)) {
                // Taken over (its source seemed gone), or admitted already: the source must not resume it.
                throw new LoadFailure(Reason.BAD_REQUEST, "'" + profile + "' runs on node '" + kernel.nodeId()
                        + "' already (taken over, or handed over before); it is not waiting for a hand-over");
            }
            // Nothing of it here: the source may resume it (see MigrationSource).
            throw new LoadFailure(Reason.UNKNOWN_COMPONENT, "no migrated '" + profile + "' waits for its hand-over on"
                    + " node '" + kernel.nodeId() + "' and none runs here (not installed, or given up after"
                    + " handoverWait)");
        }
        try {
            kernel.admit(arrival.arrival(), step.forwarded());
        } catch (RuntimeException e) {
            throw new LoadFailure(Reason.BAD_REQUEST, "'" + profile + "' cannot be admitted on node '"
                    + kernel.nodeId() + "': " + e.getMessage());
        }
        // A forwarded message refused on the way would never come: admit anyway after a step's time.
        CompletableFuture.delayedExecutor(config.migrationStepTimeoutNs(), TimeUnit.NANOSECONDS)
                .execute(() -> admitAnyway(profile, arrival.arrival()));
        String type = arrival.loaded().type().getName();
        return arrival.firstHandlingNs()
                .completeOnTimeout(-1L, config.firstMessageWaitNs(), TimeUnit.NANOSECONDS)
                .thenApplyAsync(firstNs -> {
                    installed.accept(profile, arrival.loaded().loader());
                    long epochNs = firstNs < 0 ? -1
                            : kernel.clock().epochNanos() - (kernel.clock().nanoTime() - firstNs);
                    return new MigrationStepDone(Phase.HANDOVER, profile, type, -1, epochNs);
                }, continuations);
    }

    private void admitAnyway(Profile profile, Profile arrivalProfile) {
        try {
            kernel.admit(arrivalProfile, 0);
            log.warn("node {}: '{}' admitted after a step's time without every forwarded message (one was refused"
                    + " on the way?)", kernel.nodeId(), profile);
        } catch (RuntimeException e) {
            // The usual case: admitted already, and its arrival profile is gone; or removed meanwhile.
            log.trace("node {}: '{}' needs no late admission: {}", kernel.nodeId(), profile, e.toString());
        }
    }

    /** The INSTALL did not come in time: the source resumed the component, or died; drop the instance. */
    private void forgetPrepared(Profile profile, Prepared ready) {
        if (!prepared.remove(profile, ready)) {
            return; // installed, or replaced by a later PREPARE
        }
        abandoned.increment();
        log.warn("node {}: the instance prepared for migrated '{}' was not installed within {} ms; discarding it (its"
                + " source, node '{}', resumed it or is gone)", kernel.nodeId(), profile,
                TimeUnit.NANOSECONDS.toMillis(preparedKeepNs(config)), ready.fromNode());
        ready.loaded().discard();
    }

    /**
     * Until the hand-over (or the give-up), looks every {@link #SOURCE_WATCH_NS} whether the
     * source's process left without a goodbye: it then never sends the hand-over, and, if it left
     * before it could have resumed the component (its INSTALL step failing), never resumed it
     * either, holding (or having forwarded) the component since it sent the INSTALL. Once it has
     * stayed away for a step's time (a live source whose connection was reset is back by then), the
     * component is taken over here.
     */
    private void watchSource(Profile profile, Arrived arrival) {
        CompletableFuture.delayedExecutor(SOURCE_WATCH_NS, TimeUnit.NANOSECONDS).execute(() -> {
            if (arrived.get(profile) != arrival) {
                return; // handed over, taken over or given up
            }
            long goneNs = goneBeforeResumeNs(arrival);
            if (goneNs >= sourceGoneAfterNs(config)) {
                takeOver(profile, arrival);
            } else {
                watchSource(profile, arrival);
            }
        });
    }

    /**
     * How long ago the source's process left without a goodbye, if it left before it could have
     * resumed the component; -1 if it did not leave so (or left later: it may have resumed it, its
     * INSTALL step having failed, and then died with it).
     */
    private long goneBeforeResumeNs(Arrived arrival) {
        Optional<Duration> gone = sourceGone.apply(arrival.fromNode());
        if (gone.isEmpty()) {
            return -1;
        }
        long goneNs = gone.get().toNanos();
        return kernel.clock().nanoTime() - goneNs < arrival.mayResumeAtNs() ? goneNs : -1;
    }

    /** The source left after the INSTALL: admits the component with what it forwarded, if anything. */
    private void takeOver(Profile profile, Arrived arrival) {
        if (!arrived.remove(profile, arrival)) {
            return;
        }
        try {
            kernel.admit(arrival.arrival(), 0);
        } catch (RuntimeException e) {
            log.warn("node {}: taking migrated '{}' over failed: {}", kernel.nodeId(), profile, e.toString());
            return;
        }
        installed.accept(profile, arrival.loaded().loader());
        takenOver.increment();
        log.warn("node {}: the source of migrated '{}', node '{}', left without a goodbye after its INSTALL, before"
                + " it could have resumed it (its process ended?), and has not come back for {} ms; it runs here now,"
                + " from the state handed over; what the source still held of its messages is lost with it",
                kernel.nodeId(), profile, arrival.fromNode(), TimeUnit.NANOSECONDS.toMillis(sourceGoneAfterNs(config)));
    }

    /**
     * The hand-over did not come in time: the source resumed the component (or died after it could
     * have); remove this copy. Put off while the source is gone in a way that makes the watch take
     * the component over.
     */
    private void giveUp(Profile profile, Arrived arrival) {
        if (arrived.get(profile) != arrival) {
            return;
        }
        if (goneBeforeResumeNs(arrival) >= 0) {
            CompletableFuture.delayedExecutor(SOURCE_WATCH_NS, TimeUnit.NANOSECONDS)
                    .execute(() -> giveUp(profile, arrival));
            return;
        }
        if (!arrived.remove(profile, arrival)) {
            return;
        }
        log.warn("node {}: migrated '{}' was not handed over within {} ms; removing it (its source, node '{}',"
                + " resumed it or is gone)", kernel.nodeId(), profile,
                TimeUnit.NANOSECONDS.toMillis(config.handoverWaitNs()), arrival.fromNode());
        try {
            // Unregistered at once; stopped at its next boundary.
            kernel.removeAsync(arrival.arrival()).whenComplete((done, error) -> arrival.loaded().discard());
        } catch (RuntimeException e) {
            log.warn("node {}: removing migrated '{}' failed: {}", kernel.nodeId(), profile, e.toString());
        }
        abandoned.increment();
    }

    /**
     * Install and hand-over must come from the node whose PREPARE began the migration (its
     * {@code fromNode}, checked against the connection by the service before this runs).
     */
    private void requireSameSource(MigrationStep step, String fromNode) throws LoadFailure {
        if (!fromNode.equals(step.fromNode())) {
            throw new LoadFailure(Reason.REMOTE_REFUSED, "the " + step.phase() + " step of '" + step.target()
                    + "' came from node '" + step.fromNode() + "', but node '" + fromNode + "' is migrating it to node '"
                    + kernel.nodeId() + "'; only that node continues its migration");
        }
    }

    private boolean hostsLocally(Profile profile) {
        try {
            return kernel.registry().resolve(profile) instanceof Endpoint.Local local
                    && local.shell().profile().equals(profile);
        } catch (ProfileResolutionException e) {
            return false;
        }
    }
}
