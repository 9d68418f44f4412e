package io.etherware.rt.scheduling.internal;

import io.etherware.rt.scheduling.DispatcherStats;
import io.etherware.rt.stats.LatencyRecorder;
import java.util.concurrent.atomic.AtomicLong;
import java.util.concurrent.atomic.LongAdder;

/**
 * One dispatcher's time accounting. The {@code record…} methods are called only on the
 * dispatcher's own thread (single writer: no locks, no allocation); {@link #recordEnqueued()} and
 * {@link #recordBoost()} from any thread; {@link #snapshot(int)} from readers, serialized here.
 */
public final class DispatcherRecorder {

    /** Longer values are recorded as this: 60 s. */
    static final long HIGHEST_TRACKABLE_NS = 60_000_000_000L;
    private static final int SIGNIFICANT_DIGITS = 2;

    private final LatencyRecorder startLatency = new LatencyRecorder(HIGHEST_TRACKABLE_NS, SIGNIFICANT_DIGITS);
    private final LatencyRecorder execution = new LatencyRecorder(HIGHEST_TRACKABLE_NS, SIGNIFICANT_DIGITS);
    private final AtomicLong jobsRun = new AtomicLong();
    private final AtomicLong jobsParked = new AtomicLong();
    private final AtomicLong deadlineMisses = new AtomicLong();
    private final AtomicLong failures = new AtomicLong();
    private final AtomicLong dequeued = new AtomicLong();
    private final AtomicLong priorityBoosts = new AtomicLong();
    private final LongAdder enqueued = new LongAdder();

    void recordRun(long startLatencyNs, long executionNs) {
        startLatency.record(startLatencyNs);
        execution.record(executionNs);
        increment(jobsRun);
    }

    void recordParked() {
        increment(jobsParked);
    }

    void recordMiss() {
        increment(deadlineMisses);
    }

    void recordFailure() {
        increment(failures);
    }

    void recordDequeued() {
        increment(dequeued);
    }

    /** Any thread. */
    void recordEnqueued() {
        enqueued.increment();
    }

    /** Any thread. */
    void recordBoost() {
        priorityBoosts.incrementAndGet();
    }

    public long deadlineMisses() {
        return deadlineMisses.get();
    }

    public long jobsRun() {
        return jobsRun.get();
    }

    /** Reader side: everything recorded since start. */
    public synchronized DispatcherStats snapshot(int dispatcherId) {
        long queued = Math.max(0, enqueued.sum() - dequeued.get());
        return new DispatcherStats(dispatcherId, jobsRun.get(), jobsParked.get(), deadlineMisses.get(),
                failures.get(), priorityBoosts.get(), queued, startLatency.snapshot(), execution.snapshot());
    }

    /** Single writer: a release store is enough and cheaper than an atomic add. */
    private static void increment(AtomicLong counter) {
        counter.setRelease(counter.getPlain() + 1);
    }
}
