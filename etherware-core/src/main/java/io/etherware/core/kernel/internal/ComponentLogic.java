package io.etherware.core.kernel.internal;

import io.etherware.core.component.Component;
import io.etherware.core.component.ComponentContext;
import io.etherware.core.component.ComponentState;
import io.etherware.core.component.Shell.State;
import io.etherware.core.kernel.SupervisionPolicy;
import io.etherware.core.kernel.SwapTimings;
import io.etherware.core.message.Message;
import io.etherware.core.message.Profile;
import io.etherware.core.time.NodeClock;
import java.lang.invoke.MethodHandles;
import java.lang.invoke.VarHandle;
import java.util.Objects;
import java.util.concurrent.CompletableFuture;
import java.util.function.LongConsumer;
import java.util.function.Supplier;
import org.slf4j.Logger;
import org.slf4j.LoggerFactory;

/**
 * The logic of one component and what replaces it: the current {@link Component} instance, its
 * lifecycle state and counters, the handling of a message with the restart policy applied to a
 * failure, and the supervision steps that make a new instance: restart, reset, swap. The node's
 * side of a failure (its report, the escalation) is {@link Supervision}'s.
 *
 * <p>Owned by {@link LocalShell}, which decides when each step runs: every method that changes the
 * logic runs on the thread that owns the component's gate (the "owner").
 *
 * <p>Thread-safety: fields marked "owner" are touched only by the owner, whose entry and exit of
 * the gate are full fences, so they need no further synchronization. Counters are written by the
 * owner with release stores and read with acquire loads (plain moves on x86), so a reader who
 * sees a failure counted also sees the restart that followed it. Takes no lock.
 */
final class ComponentLogic {

    private static final Logger log = LoggerFactory.getLogger("io.etherware.core.kernel.Supervision");

    private static final VarHandle HANDLED;
    private static final VarHandle FAILED;
    private static final VarHandle RESTARTS;
    private static final VarHandle LAST_HANDLING_NS;

    static {
        try {
            var lookup = MethodHandles.lookup();
            HANDLED = lookup.findVarHandle(ComponentLogic.class, "handled", long.class);
            FAILED = lookup.findVarHandle(ComponentLogic.class, "failed", long.class);
            RESTARTS = lookup.findVarHandle(ComponentLogic.class, "restarts", long.class);
            LAST_HANDLING_NS = lookup.findVarHandle(ComponentLogic.class, "lastHandlingNs", long.class);
        } catch (ReflectiveOperationException e) {
            throw new ExceptionInInitializerError(e);
        }
    }

    private final String nodeId;
    private final NodeClock clock;
    private final Profile profile;
    private final String name;
    private final SupervisionPolicy policy;
    private final boolean snapshotting;
    private final ComponentContext context;
    private final Supervision supervision;

    private volatile Supplier<? extends Component> factory;
    private volatile Component logic;
    private volatile State lifecycle = State.CREATED;

    @SuppressWarnings("unused") // through HANDLED
    private long handled;
    @SuppressWarnings("unused") // through FAILED
    private long failed;
    @SuppressWarnings("unused") // through RESTARTS
    private long restarts;
    @SuppressWarnings("unused") // through LAST_HANDLING_NS
    private long lastHandlingNs;

    private ComponentState lastSnapshot; // owner
    /** When the current logic's last handling ended; for a timed swap's gap. */
    private long lastHandlingEndNs = SwapTimings.UNKNOWN_NS; // owner
    /** Told when the logic installed by a timed swap begins its first message, then cleared. */
    private LongConsumer firstHandlingProbe; // owner
    private final long[] restartTimesNs; // owner: ring of the latest restarts
    private int restartHead; // owner
    private int restartsInRing; // owner

    /**
     * Makes the first instance from {@code factory} (on the calling thread); it is started by
     * {@link #start}.
     *
     * @param context     what the instances get in {@link Component#onStart}
     * @param supervision told of failures and of an exceeded restart intensity
     */
    ComponentLogic(String nodeId, NodeClock clock, Profile profile, Supplier<? extends Component> factory,
                   SupervisionPolicy policy, ComponentContext context, Supervision supervision) {
        this.nodeId = nodeId;
        this.clock = clock;
        this.profile = profile;
        this.name = profile.toString();
        this.factory = Objects.requireNonNull(factory, "factory");
        this.policy = Objects.requireNonNull(policy, "policy");
        this.snapshotting = policy.restart() == SupervisionPolicy.Restart.FROM_SNAPSHOT;
        this.restartTimesNs = new long[policy.restart() == SupervisionPolicy.Restart.STOP ? 0 : policy.maxRestarts()];
        this.context = context;
        this.supervision = supervision;
        this.logic = newLogic(factory);
    }

    /** What makes new instances: the one given at the start, or the last swap's. */
    Supplier<? extends Component> factory() {
        return factory;
    }

    SupervisionPolicy policy() {
        return policy;
    }

    State state() {
        return lifecycle;
    }

    long handledCount() {
        return (long) HANDLED.getAcquire(this);
    }

    long failedCount() {
        return (long) FAILED.getAcquire(this);
    }

    long restartCount() {
        return (long) RESTARTS.getAcquire(this);
    }

    long lastHandlingNs() {
        return (long) LAST_HANDLING_NS.getAcquire(this);
    }

    Class<? extends Component> logicType() {
        return logic.getClass();
    }

    /** Owner: reports the first handling of the logic to {@code probe} (see {@link SwapTimings}). */
    void expectFirstHandling(LongConsumer probe) {
        firstHandlingProbe = probe;
    }

    /** Starts the first instance (once; owner). */
    void start() {
        lifecycle = State.STARTING;
        try {
            Component current = logic;
            current.onStart(context);
            lastSnapshot = snapshotting ? current.snapshot() : null;
            lifecycle = State.RUNNING;
        } catch (Throwable failure) {
            lifecycle = State.FAILED;
            log.error("node {}: component '{}' failed to start; it is FAILED and messages to it are undeliverable",
                    nodeId, name, failure);
        }
    }

    /** For a component removed before it was started. */
    void markStopped() {
        lifecycle = State.STOPPED;
    }

    /** Owner: stops the logic if it runs; the component is STOPPED then. */
    void stopRunning() {
        if (lifecycle == State.RUNNING) {
            lifecycle = State.STOPPING;
            stopLogic(logic);
        }
        lifecycle = State.STOPPED;
    }

    /** Owner: the component's state now, or null. */
    ComponentState snapshot() throws Exception {
        return logic.snapshot();
    }

    /** At close, with the dispatchers stopped: stops the component if it runs. */
    void stopForClose() {
        State was = lifecycle;
        if (was == State.RUNNING) {
            lifecycle = State.STOPPING;
            stopLogic(logic);
            lifecycle = State.STOPPED;
        } else if (was != State.FAILED) {
            lifecycle = State.STOPPED;
        }
    }

    /** Owner: handles {@code message} with the running logic; a failure goes to the policy. */
    void handle(Message message, long nowNs) {
        Component current = logic;
        LongConsumer probe = firstHandlingProbe;
        long probeStartNs = 0;
        if (probe != null) {
            // Read here, inside the gate, not the dispatcher's take time: that may precede the
            // end of the swap for a job taken while the swap was finishing.
            firstHandlingProbe = null;
            probeStartNs = clock.nanoTime();
        }
        try {
            current.onMessage(message, context);
            if (snapshotting) {
                lastSnapshot = current.snapshot();
            }
            HANDLED.setRelease(this, handled + 1);
        } catch (Throwable failure) {
            onFailure(message, failure, nowNs);
        }
        long endNs = clock.nanoTime();
        lastHandlingEndNs = endNs;
        LAST_HANDLING_NS.setRelease(this, endNs - nowNs);
        if (probe != null) {
            tellFirstHandling(probe, probeStartNs);
        }
    }

    private void tellFirstHandling(LongConsumer probe, long startNs) {
        try {
            probe.accept(startNs);
        } catch (Throwable failure) {
            log.warn("node {}: the first-handling callback of the swap of '{}' threw; ignored", nodeId, name,
                    failure);
        }
    }

    // ---------------------------------------------------------------- supervision (owner thread)

    private void onFailure(Message message, Throwable failure, long nowNs) {
        long failures = failed + 1;
        supervision.reportFailure(profile, message, failure, failures);
        try {
            applyPolicy(failure, nowNs);
        } finally {
            // Counted once the policy is applied, so a reader who sees the failure sees its restart.
            FAILED.setRelease(this, failures);
        }
    }

    private void applyPolicy(Throwable failure, long nowNs) {
        if (policy.restart() == SupervisionPolicy.Restart.STOP) {
            lifecycle = State.STOPPING;
            stopLogic(logic);
            lifecycle = State.FAILED;
            log.error("node {}: component '{}' stopped after its failure (policy STOP); messages to it are undeliverable",
                    nodeId, name);
        } else if (withinIntensity(nowNs)) {
            restart(nowNs);
        } else {
            log.error("node {}: component '{}' failed more than {} times within {} ms; escalating to the node",
                    nodeId, name, policy.maxRestarts(), policy.windowNs() / 1_000_000);
            supervision.escalate(profile, failure);
        }
    }

    /** Whether one more restart stays within {@code maxRestarts} per {@code windowNs}. */
    private boolean withinIntensity(long nowNs) {
        int max = restartTimesNs.length;
        if (max == 0) {
            return false;
        }
        // When the ring is full, restartHead points at the oldest of the last max restarts.
        return restartsInRing < max || nowNs - restartTimesNs[restartHead] >= policy.windowNs();
    }

    private void restart(long nowNs) {
        restartTimesNs[restartHead] = nowNs;
        restartHead = (restartHead + 1) % restartTimesNs.length;
        restartsInRing = Math.min(restartsInRing + 1, restartTimesNs.length);
        long count = restarts + 1;
        RESTARTS.setRelease(this, count);

        boolean fromSnapshot = snapshotting && lastSnapshot != null;
        lifecycle = State.STARTING;
        stopLogic(logic);
        try {
            Component fresh = newLogic(factory);
            if (fromSnapshot) {
                fresh.restore(lastSnapshot);
            }
            fresh.onStart(context);
            logic = fresh;
            lifecycle = State.RUNNING;
            log.warn("node {}: component '{}' restarted {} (restart {}, {} within the last {} ms)", nodeId, name,
                    fromSnapshot ? "from its last snapshot" : "fresh", count, restartsInRing, policy.windowNs() / 1_000_000);
        } catch (Throwable failure) {
            lifecycle = State.FAILED;
            log.error("node {}: component '{}' could not be restarted; escalating to the node", nodeId, name, failure);
            supervision.escalate(profile, failure);
        }
    }

    /**
     * Owner, for the node-wide reset (the Management Tree's reset): a fresh instance, started,
     * with its restart history forgotten.
     */
    void reset() {
        if (lifecycle == State.RUNNING) {
            lifecycle = State.STOPPING;
            stopLogic(logic);
        }
        restartHead = 0;
        restartsInRing = 0;
        lastSnapshot = null;
        firstHandlingProbe = null; // the swapped-in logic is gone before its first message
        lifecycle = State.STARTING;
        try {
            Component fresh = newLogic(factory);
            fresh.onStart(context);
            lastSnapshot = snapshotting ? fresh.snapshot() : null;
            logic = fresh;
            lifecycle = State.RUNNING;
            log.info("node {}: component '{}' reset", nodeId, name);
        } catch (Throwable failure) {
            lifecycle = State.FAILED;
            log.error("node {}: component '{}' failed to start after the reset; it is FAILED", nodeId, name, failure);
        }
    }

    /**
     * Owner, for an upgrade: snapshot, new instance, restore, start, swap, stop the old one. If
     * anything before the swap throws, the old logic stays and {@code done} fails. With a
     * {@code probe}, the new logic's first handling is reported to it (see {@link SwapTimings}).
     */
    void swap(Supplier<? extends Component> newFactory, CompletableFuture<SwapTimings> done, LongConsumer probe) {
        long startNs = clock.nanoTime();
        if (lifecycle != State.RUNNING) {
            done.completeExceptionally(new IllegalStateException(
                    "component '" + name + "' is " + lifecycle + "; only a RUNNING component can be swapped"));
            return;
        }
        Component old = logic;
        Component fresh;
        ComponentState freshSnapshot;
        int schemaVersion = -1;
        try {
            ComponentState state = old.snapshot();
            if (state != null) {
                schemaVersion = state.schemaVersion();
            }
            fresh = newLogic(newFactory);
            if (state != null) {
                fresh.restore(state);
            }
            fresh.onStart(context);
            freshSnapshot = snapshotting ? fresh.snapshot() : null;
        } catch (Throwable failure) {
            log.warn("node {}: swap of component '{}' rolled back; {} stays: {}", nodeId, name,
                    old.getClass().getName(), failure.toString());
            done.completeExceptionally(failure);
            return;
        }
        logic = fresh;
        factory = newFactory;
        lastSnapshot = freshSnapshot;
        long oldEndNs = lastHandlingEndNs;
        lastHandlingEndNs = SwapTimings.UNKNOWN_NS;
        firstHandlingProbe = probe;
        stopLogic(old);
        // Debug, not info: this runs inside the pause, where a console write costs tens of
        // microseconds; the caller of the swap reports it (EtherwareNode.swap, the management service).
        log.debug("node {}: component '{}' swapped from {} to {}", nodeId, name, old.getClass().getName(),
                fresh.getClass().getName());
        done.complete(new SwapTimings(oldEndNs, startNs, clock.nanoTime(), schemaVersion));
    }

    private Component newLogic(Supplier<? extends Component> from) {
        return Objects.requireNonNull(from.get(), () -> "the factory of component '" + name + "' returned null");
    }

    private void stopLogic(Component stopping) {
        try {
            stopping.onStop();
        } catch (Throwable failure) {
            log.warn("node {}: onStop of component '{}' threw; ignored", nodeId, name, failure);
        }
    }
}
