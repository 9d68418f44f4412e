package io.etherware.rt.scheduling.internal;

import io.etherware.core.scheduler.JobRunner;
import io.etherware.core.time.NodeClock;
import io.etherware.rt.scheduling.DeadlineMissHandler;
import java.util.Objects;
import java.util.concurrent.ConcurrentMap;
import java.util.concurrent.atomic.AtomicLong;

/**
 * What the dispatchers of one started scheduler share: the kernel's runner, the clock, the
 * lifecycle state, the per-component recorders, and the submitted/finished counts that tell
 * shutdown when the module is quiet.
 *
 * <p>Thread-safe. {@link #dispatchers} is set once, before any dispatcher thread starts.
 */
public final class DispatchContext {

    /** Taking jobs. */
    public static final int RUNNING = 0;
    /** Shutting down: only jobs that hold their component's reservation are still taken. */
    public static final int DRAINING = 1;
    /** Stopped: dispatchers take nothing more and exit. */
    public static final int ABORTED = 2;

    final JobRunner runner;
    final NodeClock clock;
    final ConcurrentMap<String, ComponentRecorder> components;
    final DeadlineMissHandler missHandler;
    final boolean priorityInheritance;
    /** Jobs offered to any dispatcher, including refused ones. Incremented before the offer. */
    final AtomicLong submitted = new AtomicLong();
    /** Jobs refused, run, parked or failed. Incremented after the runner returned. */
    final AtomicLong finished = new AtomicLong();
    volatile int state = RUNNING;
    private Dispatcher[] dispatchers;

    public DispatchContext(JobRunner runner, NodeClock clock, ConcurrentMap<String, ComponentRecorder> components,
                           DeadlineMissHandler missHandler, boolean priorityInheritance) {
        this.runner = Objects.requireNonNull(runner, "runner");
        this.clock = Objects.requireNonNull(clock, "clock");
        this.components = components;
        this.missHandler = missHandler;
        this.priorityInheritance = priorityInheritance;
    }

    public void setDispatchers(Dispatcher[] all) {
        this.dispatchers = all.clone();
    }

    Dispatcher[] dispatchers() {
        return dispatchers;
    }

    public NodeClock clock() {
        return clock;
    }

    public int state() {
        return state;
    }

    public void setState(int newState) {
        state = newState;
    }

    /**
     * Whether every job ever offered has been refused, run, parked or has failed, so nothing is
     * queued or running. Reads {@code finished} before {@code submitted}: a job in flight was
     * submitted before and finishes after, so it keeps them apart.
     */
    public boolean isQuiet() {
        long finishedJobs = finished.get();
        return finishedJobs == submitted.get();
    }

    /** Offered jobs that are neither finished nor in {@code collected}: submitters still in flight. */
    public long unaccounted(long collected) {
        return submitted.get() - finished.get() - collected;
    }
}
