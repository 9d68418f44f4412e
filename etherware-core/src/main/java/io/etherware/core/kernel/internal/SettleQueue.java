package io.etherware.core.kernel.internal;

import io.etherware.core.time.NodeClock;
import java.util.ArrayDeque;
import java.util.concurrent.atomic.AtomicInteger;
import java.util.function.BooleanSupplier;

/**
 * The holds and swaps of one component that wait for it to be quiescent, each until its deadline
 * at the latest; and the counts they look at. Quiescent means: the component awaits no outcome of
 * its requests; for a hold, also: no message from another component is queued for it (one that
 * its own handler sent itself does not count, so a component that keeps itself going still
 * settles). An action runs at a message boundary of the component, in the order the actions
 * were asked for.
 *
 * <p>Why a hold also waits for the messages already queued: a hold is what a migration takes
 * first, and a message queued at the hold is carried across the network after the component's
 * state, to be handled there once the move is done, perhaps past its deadline (a control loop's
 * Tick queued at the hold becomes a lost cycle). Handled here, before the hold, it costs the
 * handling. A swap does not wait for them: the new logic handles them as soon.
 *
 * <p>Owned by {@link LocalShell}, which calls the boundary methods when it owns its gate.
 *
 * <p>Thread-safety: the queue is touched only by the thread that owns the component's gate (the
 * "owner"), whose entry and exit are full fences; the counts are atomic and change on any
 * thread. Takes no lock.
 */
final class SettleQueue {

    /**
     * A hold or swap waiting for the component to be quiescent, until {@code byNs} at the latest;
     * {@code drains} if it also waits for the messages of other components queued for it.
     */
    private record Pending(Runnable action, long byNs, boolean drains) {
    }

    private final NodeClock clock;
    /** Whether the component is held (its queued messages cannot run until it is released). */
    private final BooleanSupplier held;
    /** Requests of this component whose outcome has not been handed to it yet. */
    private final AtomicInteger awaitingOutcomes = new AtomicInteger();
    /** Messages from other components queued or kept for this one, not yet run or forwarded. */
    private final AtomicInteger othersQueued = new AtomicInteger();
    /** The holds and swaps waiting for quiescence ({@link #whenSettled}), in request order; owner. */
    private final ArrayDeque<Pending> pendingActions = new ArrayDeque<>();

    SettleQueue(NodeClock clock, BooleanSupplier held) {
        this.clock = clock;
        this.held = held;
    }

    /** A request of this component was registered: its outcome is awaited. Any thread. */
    void requestSent() {
        awaitingOutcomes.incrementAndGet();
    }

    /** The outcome of a request of this component was handed to it, or the request was never sent. */
    void requestSettled() {
        awaitingOutcomes.decrementAndGet();
    }

    /** A message from another component was queued for this one ({@code +1}), or left it ({@code -1}). */
    void othersQueued(int sign) {
        othersQueued.addAndGet(sign);
    }

    /**
     * Owner, at a boundary: queues {@code action} behind those already waiting, then runs, in
     * order, every waiting action whose turn has come: all of them if the component is quiescent
     * for them, else those whose {@code byNs} has passed (or all, if {@code now}), stopping at the
     * first that must wait, so that a later hold or swap never runs before an earlier one. Every
     * later boundary tries again. An action must tolerate running after it is no longer wanted
     * (the deadline's timer tries again too).
     *
     * @param drains whether the action also waits for the messages of other components already
     *               queued for this one to be handled (a hold), or only for the outcomes of its
     *               requests (a swap)
     */
    void whenSettled(Runnable action, long byNs, boolean now, boolean drains) {
        pendingActions.addLast(new Pending(action, byNs, drains));
        runSettled(now);
    }

    /** Owner, at the end of a job: the waiting actions whose turn has come, in order. */
    void runDue() {
        if (!pendingActions.isEmpty()) {
            runSettled(false);
        }
    }

    /** Owner, at a boundary: the waiting actions whose turn has come, in order. */
    private void runSettled(boolean now) {
        while (!pendingActions.isEmpty()) {
            Pending head = pendingActions.peekFirst();
            if (!now && !settledFor(head) && clock.nanoTime() - head.byNs() < 0) {
                return;
            }
            pendingActions.pollFirst();
            head.action().run();
        }
    }

    /** Whether the component is quiescent for {@code pending}. */
    private boolean settledFor(Pending pending) {
        if (awaitingOutcomes.get() > 0) {
            return false;
        }
        return !pending.drains() || othersQueued.get() <= 0 || held.getAsBoolean();
    }

    /**
     * Owner, at a boundary: the deadline of {@code action} has passed; runs it and every action
     * queued before it (those, if still pending, are due no later), in order.
     */
    void settleDeadline(Runnable action) {
        boolean queued = false;
        for (Pending pending : pendingActions) {
            if (pending.action() == action) {
                queued = true;
                break;
            }
        }
        if (!queued) {
            return; // it ran already
        }
        while (!pendingActions.isEmpty()) {
            Pending head = pendingActions.pollFirst();
            head.action().run();
            if (head.action() == action) {
                break;
            }
        }
        runSettled(false);
    }
}
