package io.etherware.core.kernel.internal;

import io.etherware.core.component.Component;
import io.etherware.core.component.ComponentState;
import io.etherware.core.component.Shell;
import io.etherware.core.kernel.Endpoint;
import io.etherware.core.kernel.OrderMarker;
import io.etherware.core.kernel.SupervisionPolicy;
import io.etherware.core.kernel.SwapTimings;
import io.etherware.core.message.Message;
import io.etherware.core.message.Profile;
import io.etherware.core.scheduler.Job;
import java.lang.invoke.MethodHandles;
import java.lang.invoke.VarHandle;
import java.util.List;
import java.util.Objects;
import java.util.concurrent.CompletableFuture;
import java.util.concurrent.atomic.AtomicBoolean;
import java.util.function.LongConsumer;
import java.util.function.Supplier;

/**
 * The {@link Shell} of a component on this node: its {@link ComponentGate} (one job at a time,
 * across all dispatchers), its queue count and relocation, the ordering of a migrated arrival, and
 * when the steps on its logic run (start, handling, reset, swap, stop), each on the thread that
 * owns the gate. The logic itself, its lifecycle state, counters and restart policy are
 * {@link ComponentLogic}'s.
 *
 * <p>A message waits for its component at most for the handling in progress plus the more urgent
 * messages already waiting for it (see {@link ComponentGate}).
 *
 * <p>Thread-safety: fields marked "owner" are touched only by the thread that owns the gate,
 * whose entry and exit are full fences, so they need no further synchronization. The queue
 * count is changed by CAS from any thread; no method takes a lock of its own (the gate's lock is
 * the gate's).
 */
public final class LocalShell implements Shell {

    private static final VarHandle QUEUED;
    /** In {@link #queued}: the profile now routes past this shell; send straight to {@link #forwardTo}. */
    private static final int DIRECT = 1 << 30;

    static {
        try {
            QUEUED = MethodHandles.lookup().findVarHandle(LocalShell.class, "queued", int.class);
        } catch (ReflectiveOperationException e) {
            throw new ExceptionInInitializerError(e);
        }
    }

    private final KernelCore kernel;
    /** Where the messages of a component that does not run go. */
    private final Delivery delivery;
    private final Profile profile;
    private final String name;
    private final Endpoint.Local endpoint;
    private final ComponentGate gate;
    /** The component's logic, lifecycle state, counters and restart policy. */
    private final ComponentLogic logic;
    private final AtomicBoolean started = new AtomicBoolean();

    private volatile boolean removed;
    /**
     * Jobs of this component submitted and not yet run (queued at a dispatcher, or kept at the
     * gate), plus {@link #DIRECT} once a relocation has switched the profile to its route.
     */
    @SuppressWarnings("unused") // through QUEUED
    private volatile int queued;

    /** The ordering of a component added by migration ({@link #arriveHeld}); null otherwise. */
    private volatile ArrivalPen pen;

    /** Where a relocated component's messages go; null unless relocated. */
    private volatile Endpoint.Remote forwardTo;
    /** Completes when a relocation has switched the profile to its route; owner or last job. */
    private CompletableFuture<Void> switched;
    private ProfileTable relocationRegistry;
    /** Set once a relocation's switch has pointed the profile at its route. */
    private volatile boolean switchedOver;
    /** Set once {@link KernelCore#reinstate} brought the component back from a relocation. */
    private final AtomicBoolean reinstated = new AtomicBoolean();

    /** The holds and swaps waiting for the component to be quiescent. */
    private final SettleQueue settling;

    LocalShell(KernelCore kernel, Profile profile, Supplier<? extends Component> factory, SupervisionPolicy policy) {
        this.kernel = kernel;
        this.delivery = kernel.delivery();
        this.profile = Objects.requireNonNull(profile, "profile");
        this.name = profile.toString();
        Objects.requireNonNull(factory, "factory");
        Objects.requireNonNull(policy, "policy");
        this.endpoint = new Endpoint.Local(this);
        this.gate = new ComponentGate(kernel, name);
        this.settling = new SettleQueue(kernel.clock(), gate::isHeld);
        this.logic = new ComponentLogic(kernel.nodeId(), kernel.clock(), profile, factory, policy,
                new ShellContext(kernel, this), kernel.supervision());
    }

    // ---------------------------------------------------------------- Shell

    @Override
    public Profile profile() {
        return profile;
    }

    @Override
    public State state() {
        return logic.state();
    }

    @Override
    public long handledCount() {
        return logic.handledCount();
    }

    @Override
    public long failedCount() {
        return logic.failedCount();
    }

    @Override
    public long restartCount() {
        return logic.restartCount();
    }

    @Override
    public long lastHandlingNs() {
        return logic.lastHandlingNs();
    }

    @Override
    public Class<? extends Component> logicType() {
        return logic.logicType();
    }

    @Override
    public String toString() {
        return "Shell[" + name + ", " + logic.state() + "]";
    }

    String name() {
        return name;
    }

    Endpoint.Local endpoint() {
        return endpoint;
    }

    boolean isRemoved() {
        return removed;
    }

    /** Whether {@code host} relocated this component (the switch may be still to come). */
    boolean relocatedBy(KernelCore host) {
        return kernel == host && forwardTo != null;
    }

    /** Whether a relocation has pointed the profile at its route. */
    boolean hasSwitched() {
        return switchedOver;
    }

    /** For {@link KernelCore#reinstate}: true the first time only. */
    boolean claimReinstatement() {
        return reinstated.compareAndSet(false, true);
    }

    /** What makes the component's instances (for {@link KernelCore#reinstate}). */
    Supplier<? extends Component> factory() {
        return logic.factory();
    }

    SupervisionPolicy policy() {
        return logic.policy();
    }

    // ---------------------------------------------------------------- the gate

    /** See {@link ComponentGate#enterOrPark}. */
    boolean acquireOrPark(Job job) {
        return gate.enterOrPark(job);
    }

    /**
     * Before a message for this component is submitted to the scheduler: counts it, or returns
     * false if the profile has been switched to a relocation's route, which then takes the message
     * directly ({@link #forwardRoute()}): every message submitted before the switch has been
     * forwarded by then, so a sender's later messages cannot overtake its earlier ones.
     */
    boolean enterQueue() {
        while (true) {
            int current = queued;
            if ((current & DIRECT) != 0) {
                return false;
            }
            if (QUEUED.compareAndSet(this, current, current + 1)) {
                return true;
            }
        }
    }

    /** A counted job will not run (the scheduler refused it). */
    void leaveQueue() {
        int left = (int) QUEUED.getAndAdd(this, -1) - 1;
        if (left == 0 && forwardTo != null) {
            trySwitch();
        }
    }

    /** The route of a relocated component, once the profile points at it. */
    io.etherware.core.kernel.RemoteRoute forwardRoute() {
        return forwardTo.route();
    }

    /** Runs a job that owns the gate, then leaves the gate. */
    void execute(Job job, long nowNs) {
        boolean counted = job.target() == this;
        try {
            if (counted) {
                handle(job.message(), nowNs);
            } else {
                ((PendingRequest) job.target()).settle();
            }
        } finally {
            if (counted) {
                leftJob(job);
            }
            settling.runDue();
            gate.leave();
        }
    }

    /** See {@link SettleQueue#requestSent}. */
    void requestSent() {
        settling.requestSent();
    }

    /** See {@link SettleQueue#requestSettled}. */
    void requestSettled() {
        settling.requestSettled();
    }

    /**
     * Owner, at a boundary: holds now and completes {@code held}, unless it is done already; fails
     * it if the component was removed meanwhile (a hold then would keep the jobs still queued for
     * it at a gate no profile leads to, for good).
     */
    void hold(CompletableFuture<Void> held) {
        if (held.isDone()) {
            return;
        }
        if (removed) {
            held.completeExceptionally(new IllegalStateException("'" + name + "' was removed before it could be held"));
            return;
        }
        gate.hold();
        held.complete(null);
    }

    /** See {@link SettleQueue#whenSettled}. */
    void whenSettled(Runnable action, long byNs, boolean now, boolean drains) {
        settling.whenSettled(action, byNs, now, drains);
    }

    /**
     * A job of {@code message} was made for this component ({@code +1}), or left its queue count
     * ({@code -1}: ran, forwarded, or refused): counts its bytes from the network, and whether it
     * came from another component (see {@link SettleQueue}).
     */
    void countQueued(Message message, int sign) {
        delivery.countInbound(message, sign);
        Profile sender = message.sender();
        if (sender != profile && !profile.equals(sender)) {
            settling.othersQueued(sign);
        }
    }

    /** See {@link SettleQueue#settleDeadline}. */
    void settleDeadline(Runnable action) {
        settling.settleDeadline(action);
    }

    /** A counted job ran or was forwarded. */
    private void leftJob(Job job) {
        if (job.sequence() >= Delivery.PEN_OFFSET) {
            pen.leftPenned();
        }
        countQueued(job.message(), -1);
        leaveQueue();
    }

    /** See {@link ComponentGate#atBoundary}. */
    void atBoundary(Runnable action) {
        gate.atBoundary(action);
    }

    /**
     * Before start, by the thread that adds a migrated component (it owns the gate until start):
     * keep arrivals from the start on, report the first handling to {@code probe}, and pen the
     * messages that do not come to {@code arrivalProfile} (see {@link ArrivalPen}); once every
     * message the source sent there is in, run {@code onAllArrived}.
     */
    void arriveHeld(Profile arrivalProfile, LongConsumer probe, Runnable onAllArrived) {
        pen = new ArrivalPen(arrivalProfile, gate::release, onAllArrived, job -> delivery.submit(job, this));
        gate.hold();
        logic.expectFirstHandling(probe);
    }

    /** The ordering of a migrated component, or null. */
    ArrivalPen pen() {
        return pen;
    }

    /**
     * Why the component may not be held or moved yet, or null: one still arriving by migration
     * would leave the messages its source forwards to come in after it left, behind later ones.
     *
     * @param what the refused operation, for the message
     */
    IllegalStateException stillArriving(String what) {
        ArrivalPen arrived = pen;
        return arrived == null || arrived.isAdmitted() ? null : new IllegalStateException("'" + name
                + "' is still arriving by migration (not yet handed over here); " + what + " it once it runs here");
    }

    /** For a job about to be made: whether it is penned (see {@link ArrivalPen#pens}). */
    boolean pens(Message message) {
        ArrivalPen arrived = pen;
        return arrived != null && arrived.pens(message);
    }

    /** Ends a hold; the kept jobs are delivered in urgency order, exactly once. */
    void release() {
        gate.release();
    }

    /** See {@link ComponentGate#close()}; with the jobs an arrival still deferred. */
    List<Job> closeGate() {
        List<Job> left = gate.close();
        ArrivalPen arrived = pen;
        if (arrived != null) {
            left.addAll(arrived.drain());
        }
        return left;
    }

    /** Leaving before an admission: the deferred jobs follow the kept ones (see {@link ArrivalPen#flush}). */
    private void endDeferral() {
        ArrivalPen arrived = pen;
        if (arrived != null) {
            arrived.flush();
        }
    }

    // ---------------------------------------------------------------- lifecycle

    /** Starts the component on the calling thread (once), then lets waiting messages in. */
    void start() {
        if (!started.compareAndSet(false, true)) {
            return;
        }
        logic.start();
        gate.leave();
    }

    /** For a component removed before it was started: marks it stopped; false if it had started. */
    boolean cancelIfUnstarted() {
        if (!started.compareAndSet(false, true)) {
            return false;
        }
        removed = true;
        logic.markStopped();
        endDeferral();
        gate.endHoldOnLeave(); // an arrival's kept jobs are resolved anew, as at a removal
        gate.leave();
        return true;
    }

    /**
     * Boundary action of removal: stops the component and ends a hold, so the kept messages, and
     * any that still reach this shell, are resolved anew (they follow the profile elsewhere, or
     * go back to their senders as undeliverable).
     */
    void remove() {
        removed = true;
        logic.stopRunning();
        endDeferral(); // they park behind the kept ones and are resolved anew in turn
        gate.endHoldOnLeave();
    }

    /**
     * Boundary action of a migration: stops the component and forwards the kept messages to
     * {@code to}, in urgency order. Messages still queued at dispatchers for it, and any
     * submitted meanwhile, are forwarded in turn when they are taken; once none is left, the
     * profile is pointed at {@code to} ({@code done} completes) and later messages go there
     * directly. So no message sent to the profile through this node overtakes an earlier one of
     * the same sender and urgency.
     */
    void relocate(ProfileTable registry, Endpoint.Remote to, CompletableFuture<Void> done) {
        removed = true;
        logic.stopRunning();
        relocationRegistry = registry;
        switched = done;
        forwardTo = to;
        // New arrivals park at the gate meanwhile, so the kept messages go out first.
        gate.drainKept(() -> { }, kept -> {
            if (kept.target() == this) {
                delivery.deliverRemote(kept.message(), to.route());
                if (kept.sequence() >= Delivery.PEN_OFFSET) {
                    pen.leftPenned();
                }
                countQueued(kept.message(), -1);
                QUEUED.getAndAdd(this, -1);
            } else {
                // The outcome of a request this (now stopped) instance made: it is local.
                ((PendingRequest) kept.target()).settle();
            }
        });
        if ((int) QUEUED.getVolatile(this) == 0) {
            trySwitch();
        }
    }

    /** Points the profile at the relocation's route if no job of this component is left. */
    private void trySwitch() {
        if (!QUEUED.compareAndSet(this, 0, DIRECT)) {
            return; // a job came meanwhile: the one that brings the count to 0 switches
        }
        CompletableFuture<Void> done = switched;
        try {
            if (!relocationRegistry.replace(profile, endpoint, forwardTo)) {
                throw new IllegalStateException("profile '" + name + "' was re-registered during the relocation");
            }
            switchedOver = true;
            done.complete(null);
        } catch (RuntimeException e) {
            done.completeExceptionally(e);
        }
    }

    /** Boundary action: the component's state now, or null. */
    ComponentState snapshotNow() throws Exception {
        return logic.snapshot();
    }

    /** At close, with the dispatchers stopped: stops the component if it runs. */
    void stopForClose() {
        logic.stopForClose();
    }

    private void handle(Message message, long nowNs) {
        if (logic.state() != State.RUNNING) {
            Endpoint.Remote to = forwardTo;
            if (to != null) {
                delivery.deliverRemote(message, to.route()); // relocated: in the order taken
            } else {
                delivery.notRunning(this, message);
            }
            return;
        }
        if (message.contents() instanceof OrderMarker) {
            // One that reached the component while it arrived, now run after the admission: what
            // its sender sent before through the source has been forwarded in by now.
            delivery.answerMarker(message);
            return;
        }
        logic.handle(message, nowNs);
    }

    // ---------------------------------------------------------------- supervision (owner thread)

    /**
     * Boundary action of the node-wide reset (the Management Tree's reset): a fresh instance,
     * started, with its restart history forgotten. Removed components stay stopped.
     */
    void reset() {
        if (removed || logic.state() == State.STOPPED || !started.get()) {
            return;
        }
        logic.reset();
    }

    /**
     * Boundary action of an upgrade: snapshot, new instance, restore, start, swap, stop the old
     * one. If anything before the swap throws, the old logic stays and {@code done} fails. With a
     * {@code probe}, the new logic's first handling is reported to it (see {@link SwapTimings}).
     */
    void swap(Supplier<? extends Component> newFactory, CompletableFuture<SwapTimings> done, LongConsumer probe) {
        logic.swap(newFactory, done, probe);
    }
}
