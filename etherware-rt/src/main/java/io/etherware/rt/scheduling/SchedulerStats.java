package io.etherware.rt.scheduling;

import io.etherware.rt.scheduling.internal.ComponentRecorder;
import io.etherware.rt.scheduling.internal.DispatcherRecorder;
import java.util.ArrayList;
import java.util.List;
import java.util.Map;
import java.util.Optional;
import java.util.TreeMap;
import java.util.concurrent.ConcurrentMap;

/**
 * Live time accounting of a {@link RealtimeScheduler}: per dispatcher (counts, start-latency and
 * execution-time histograms) and per component (counts, execution time).
 *
 * <p>Thread-safety: every method is safe from any thread and returns a snapshot the caller owns.
 * Dispatchers record on their own threads without locks (HdrHistogram single-writer recorders);
 * a read swaps the recorders' interval histograms and adds them to running totals, so reading is
 * for monitoring threads, not a per-message path.
 */
public final class SchedulerStats {

    private final List<DispatcherRecorder> dispatchers;
    private final ConcurrentMap<String, ComponentRecorder> components;

    SchedulerStats(List<DispatcherRecorder> dispatchers, ConcurrentMap<String, ComponentRecorder> components) {
        this.dispatchers = List.copyOf(dispatchers);
        this.components = components;
    }

    /**
     * Every dispatcher's snapshot.
     *
     * @return one snapshot per dispatcher, in dispatcher order; a new list the caller owns
     */
    public List<DispatcherStats> dispatchers() {
        var snapshots = new ArrayList<DispatcherStats>(dispatchers.size());
        for (int id = 0; id < dispatchers.size(); id++) {
            snapshots.add(dispatchers.get(id).snapshot(id));
        }
        return snapshots;
    }

    /**
     * One dispatcher's snapshot.
     *
     * @param dispatcherId the dispatcher, 0..n-1 of the Thread Scheduling Rule
     * @return the snapshot, with histograms the caller owns
     * @throws IndexOutOfBoundsException when there is no such dispatcher
     */
    public DispatcherStats dispatcher(int dispatcherId) {
        return dispatchers.get(dispatcherId).snapshot(dispatcherId);
    }

    /**
     * Every component that ran at least one job.
     *
     * @return the snapshots by component profile text, sorted by it; a new map the caller owns
     */
    public Map<String, ComponentStats> components() {
        var snapshots = new TreeMap<String, ComponentStats>();
        components.forEach((name, recorder) -> snapshots.put(name, recorder.snapshot(name)));
        return snapshots;
    }

    /**
     * One component's snapshot.
     *
     * @param component the component's profile text ({@code Job.targetName()})
     * @return the snapshot; empty when the component has not run a job
     */
    public Optional<ComponentStats> component(String component) {
        ComponentRecorder recorder = components.get(component);
        return recorder == null ? Optional.empty() : Optional.of(recorder.snapshot(component));
    }

    /**
     * Deadline misses over all dispatchers, without taking a snapshot.
     *
     * @return jobs that completed after their deadline since start
     */
    public long deadlineMisses() {
        long misses = 0;
        for (DispatcherRecorder recorder : dispatchers) {
            misses += recorder.deadlineMisses();
        }
        return misses;
    }

    /**
     * Jobs run over all dispatchers, without taking a snapshot.
     *
     * @return jobs run to completion since start
     */
    public long jobsRun() {
        long run = 0;
        for (DispatcherRecorder recorder : dispatchers) {
            run += recorder.jobsRun();
        }
        return run;
    }
}
