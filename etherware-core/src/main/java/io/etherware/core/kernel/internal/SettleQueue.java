package io.etherware.core.kernel.internal;

import io.etherware.core.time.NodeClock;
import java.util.ArrayDeque;
import java.util.concurrent.atomic.AtomicInteger;

/**
 * The holds and swaps of one component that wait for it to be quiescent, that is to await no
 * outcome of its requests, each until its deadline at the latest; and the count of those
 * outcomes. An action runs at a message boundary of the component, in the order the actions were
 * asked for.
 *
 * <p>Owned by {@link LocalShell}, which calls the boundary methods when it owns its gate.
 *
 * <p>Thread-safety: the queue is touched only by the thread that owns the component's gate (the
 * "owner"), whose entry and exit are full fences; the count of awaited outcomes is atomic and
 * changes on any thread. Takes no lock.
 */
final class SettleQueue {

    /** A hold or swap waiting for the component to be quiescent, until {@code byNs} at the latest. */
    private record Pending(Runnable action, long byNs) {
    }

    private final NodeClock clock;
    /** Requests of this component whose outcome has not been handed to it yet. */
    private final AtomicInteger awaitingOutcomes = new AtomicInteger();
    /** The holds and swaps waiting for quiescence ({@link #whenSettled}), in request order; owner. */
    private final ArrayDeque<Pending> pendingActions = new ArrayDeque<>();

    SettleQueue(NodeClock clock) {
        this.clock = clock;
    }

    /** A request of this component was registered: its outcome is awaited. Any thread. */
    void requestSent() {
        awaitingOutcomes.incrementAndGet();
    }

    /** The outcome of a request of this component was handed to it, or the request was never sent. */
    void requestSettled() {
        awaitingOutcomes.decrementAndGet();
    }

    /**
     * Owner, at a boundary: queues {@code action} behind those already waiting, then runs, in
     * order, every waiting action whose turn has come: all of them if the component awaits no
     * outcome of its requests, else those whose {@code byNs} has passed (or all, if {@code now}),
     * stopping at the first that must wait, so that a later hold or swap never runs before an
     * earlier one. Every later boundary tries again. An action must tolerate running after it is
     * no longer wanted (the deadline's timer tries again too).
     */
    void whenSettled(Runnable action, long byNs, boolean now) {
        pendingActions.addLast(new Pending(action, byNs));
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
            if (!now && awaitingOutcomes.get() > 0 && clock.nanoTime() - head.byNs() < 0) {
                return;
            }
            pendingActions.pollFirst();
            head.action().run();
        }
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
