package io.etherware.core.kernel.internal;

import io.etherware.core.scheduler.Job;
import java.lang.invoke.MethodHandles;
import java.lang.invoke.VarHandle;
import java.util.ArrayList;
import java.util.List;
import java.util.PriorityQueue;
import java.util.function.Consumer;
import org.slf4j.Logger;
import org.slf4j.LoggerFactory;

/**
 * The gate of one component: lets one job at a time in, across all dispatchers (design decision
 * 3), without ever blocking a dispatcher.
 *
 * <h2>How</h2>
 * One int word: {@code OWNED} (someone is inside: a handler, a boundary action, or a reserved job
 * on its way), {@code HELD} (keep arrivals, do not hand over), {@code ACTIONS} (boundary actions
 * wait) and a count of waiting jobs. A dispatcher enters with one CAS from 0 to {@code OWNED} and
 * leaves with one CAS back, without a lock, when nobody waits. Otherwise it takes the gate's
 * lock: an arriving job is parked in a priority queue ordered by the scheduler's urgency (ties in
 * arrival order) and the dispatcher moves on; the leaving owner runs the waiting boundary
 * actions, then <em>reserves</em> the most urgent waiting job (the gate stays {@code OWNED} on its
 * behalf) and submits it back to the scheduler, which runs it on its own dispatcher at its own
 * priority. A reserved job always runs when taken.
 *
 * <h2>Why reservation keeps per-source order</h2>
 * Say dispatcher D1 parked job A1 because the component was busy on D2, then took A2 (same source,
 * queued after A1) and is about to run it. If D2, on leaving, freed the gate and resubmitted A1
 * as an ordinary job, D1 could enter with A2 first. With reservation the gate stays owned for A1,
 * so A2 parks behind it (the urgency order puts A1 first) and runs after it. In general, a job
 * enters directly only when the gate is 0, that is when no job waits and none is reserved; every
 * earlier job of the same source on the same dispatcher was taken before it and has run, or it
 * waits or is reserved, so the gate is not 0.
 *
 * <h2>Bound on priority inversion</h2>
 * A job waits for its component at most for the handling in progress plus the jobs already
 * waiting that are more urgent (and the boundary actions queued before it). It never waits for
 * work of other components, and no dispatcher ever blocks on the gate.
 *
 * <p>Thread-safety: the only lock-free transitions are 0 to {@code OWNED} (anyone) and
 * {@code OWNED} to 0 (the owner); every other change happens under the lock, by CAS against the
 * value read there. Entry and exit are full fences, so state touched only by the owner needs no
 * further synchronization.
 */
final class ComponentGate {

    private static final Logger log = LoggerFactory.getLogger("io.etherware.core.kernel.Supervision");

    private static final int OWNED = 1;
    private static final int HELD = 2;
    private static final int ACTIONS = 4;
    private static final int WAITER = 8;

    private static final VarHandle STATE;

    static {
        try {
            STATE = MethodHandles.lookup().findVarHandle(ComponentGate.class, "state", int.class);
        } catch (ReflectiveOperationException e) {
            throw new ExceptionInInitializerError(e);
        }
    }

    private final KernelCore kernel;
    private final String name;
    private final Object lock = new Object();

    /** Owned by whoever adds the component until it is started. */
    @SuppressWarnings("unused") // through STATE
    private volatile int state = OWNED;
    private PriorityQueue<Job> waiting; // guarded by lock
    private List<Runnable> actions; // guarded by lock

    ComponentGate(KernelCore kernel, String name) {
        this.kernel = kernel;
        this.name = name;
    }

    /**
     * Lets {@code job} in (true: the caller now owns the gate and must {@link #leave} it), or
     * parks it (false: it comes back reserved).
     */
    boolean enterOrPark(Job job) {
        if (STATE.compareAndSet(this, 0, OWNED)) {
            return true;
        }
        synchronized (lock) {
            while (true) {
                int current = state;
                if (current == 0) {
                    if (STATE.compareAndSet(this, 0, OWNED)) {
                        return true;
                    }
                } else if (STATE.compareAndSet(this, current, current + WAITER)) {
                    if (waiting == null) {
                        waiting = new PriorityQueue<>(kernel.urgency());
                    }
                    waiting.add(job);
                    return false;
                }
            }
        }
    }

    /** Leaves the gate: frees it, or runs the boundary actions and hands over to the next job. */
    void leave() {
        if (!STATE.compareAndSet(this, OWNED, 0)) {
            leaveSlowly();
        }
    }

    private void leaveSlowly() {
        while (true) {
            List<Runnable> due = null;
            Job next = null;
            synchronized (lock) {
                int current = state;
                if ((current & ACTIONS) != 0) {
                    due = actions;
                    actions = null;
                    STATE.getAndBitwiseAnd(this, ~ACTIONS);
                } else if ((current & HELD) == 0 && current >= WAITER) {
                    next = waiting.poll();
                    STATE.getAndAdd(this, -WAITER);
                } else {
                    STATE.getAndAdd(this, -OWNED);
                    return;
                }
            }
            if (due != null) {
                due.forEach(this::runAction);
            } else if (handOver(next)) {
                return;
            }
        }
    }

    /** Submits a reserved job, which now owns the gate; false if the scheduler refused it. */
    private boolean handOver(Job next) {
        next.reserve();
        if (kernel.resubmit(next)) {
            return true;
        }
        kernel.discard(next);
        return false;
    }

    /**
     * Runs {@code action} with the gate owned, at the component's next message boundary: now on
     * the calling thread if the gate is free, else on the thread that leaves it.
     */
    void atBoundary(Runnable action) {
        synchronized (lock) {
            while (true) {
                int current = state;
                if ((current & OWNED) == 0) {
                    if (STATE.compareAndSet(this, current, current | OWNED)) {
                        break;
                    }
                } else if (STATE.compareAndSet(this, current, current | ACTIONS)) {
                    if (actions == null) {
                        actions = new ArrayList<>(2);
                    }
                    actions.add(action);
                    return;
                }
            }
        }
        runAction(action);
        leave();
    }

    private void runAction(Runnable action) {
        try {
            action.run();
        } catch (RuntimeException | Error e) {
            log.error("node {}: boundary action on component '{}' failed", kernel.nodeId(), name, e);
        }
    }

    /** Owner only: from now on, keep arrivals. */
    void hold() {
        STATE.getAndBitwiseOr(this, HELD);
    }

    /** Whether arrivals are kept (a hold); any thread, a snapshot. */
    boolean isHeld() {
        return (state & HELD) != 0;
    }

    /** Owner only: end a hold; the kept jobs are handed over when the owner leaves. */
    void endHoldOnLeave() {
        STATE.getAndBitwiseAnd(this, ~HELD);
    }

    /** Ends a hold; the kept jobs are delivered in urgency order, exactly once. */
    void release() {
        Job next = null;
        synchronized (lock) {
            while (true) {
                int current = state;
                if ((current & HELD) == 0) {
                    return;
                }
                if ((current & OWNED) == 0 && current >= WAITER) {
                    if (STATE.compareAndSet(this, current, (current & ~HELD) - WAITER + OWNED)) {
                        next = waiting.poll();
                        break;
                    }
                } else if (STATE.compareAndSet(this, current, current & ~HELD)) {
                    return; // an owner hands over when it leaves; no waiter means nothing to do
                }
            }
        }
        if (!handOver(next)) {
            leaveSlowly();
        }
    }

    /**
     * Owner only: under the gate's lock (arrivals park meanwhile), runs {@code switchOver}, ends a
     * hold and gives every kept job, in urgency order, to {@code kept}.
     */
    void drainKept(Runnable switchOver, Consumer<Job> kept) {
        synchronized (lock) {
            switchOver.run();
            STATE.getAndBitwiseAnd(this, ~HELD);
            if (waiting != null) {
                for (Job job; (job = waiting.poll()) != null; ) {
                    STATE.getAndAdd(this, -WAITER);
                    kept.accept(job);
                }
            }
        }
    }

    /**
     * At close, after the dispatchers stopped: runs the pending boundary actions, keeps the gate
     * owned for good and returns the jobs still waiting, for the kernel to count as discarded.
     */
    List<Job> close() {
        List<Runnable> due;
        List<Job> left = new ArrayList<>();
        synchronized (lock) {
            due = actions;
            actions = null;
            if (waiting != null) {
                left.addAll(waiting);
                waiting.clear();
            }
            STATE.set(this, OWNED);
        }
        if (due != null) {
            due.forEach(this::runAction);
        }
        return left;
    }
}
