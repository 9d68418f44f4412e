package io.etherware.rt.scheduling.internal;

import io.etherware.rt.scheduling.DispatcherStats;
import java.util.concurrent.atomic.AtomicLong;
import java.util.concurrent.atomic.LongAdder;
import org.HdrHistogram.Histogram;
import org.HdrHistogram.SingleWriterRecorder;

/**
 * One dispatcher's time accounting. The {@code record…} methods are called only on the
 * dispatcher's own thread (single writer: no locks, no allocation); {@link #recordEnqueued()} and
 * {@link #recordBoost()} from any thread; {@link #snapshot(int)} from readers, serialized here.
 */
public final class DispatcherRecorder {

    /** Longer values are recorded as this: 60 s. */
    static final long HIGHEST_TRACKABLE_NS = 60_000_000_000L;
    private static final int SIGNIFICANT_DIGITS = 2;

    private final SingleWriterRecorder startLatency = new SingleWriterRecorder(1, HIGHEST_TRACKABLE_NS,
            SIGNIFICANT_DIGITS);
    private final SingleWriterRecorder execution = new SingleWriterRecorder(1, HIGHEST_TRACKABLE_NS,
            SIGNIFICANT_DIGITS);
    private final AtomicLong jobsRun = new AtomicLong();
    private final AtomicLong jobsParked = new AtomicLong();
    private final AtomicLong deadlineMisses = new AtomicLong();
    private final AtomicLong failures = new AtomicLong();
    private final AtomicLong dequeued = new AtomicLong();
    private final AtomicLong priorityBoosts = new AtomicLong();
    private final LongAdder enqueued = new LongAdder();

    // Reader side, guarded by this.
    private final Histogram startLatencyTotal = new Histogram(1, HIGHEST_TRACKABLE_NS, SIGNIFICANT_DIGITS);
    private final Histogram executionTotal = new Histogram(1, HIGHEST_TRACKABLE_NS, SIGNIFICANT_DIGITS);
    // A recycled interval histogram must come from the recorder it goes back to.
    private Histogram startLatencyInterval;
    private Histogram executionInterval;

    void recordRun(long startLatencyNs, long executionNs) {
        startLatency.recordValue(clamp(startLatencyNs));
        execution.recordValue(clamp(executionNs));
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
        startLatencyInterval = startLatency.getIntervalHistogram(startLatencyInterval);
        startLatencyTotal.add(startLatencyInterval);
        executionInterval = execution.getIntervalHistogram(executionInterval);
        executionTotal.add(executionInterval);
        long queued = Math.max(0, enqueued.sum() - dequeued.get());
        return new DispatcherStats(dispatcherId, jobsRun.get(), jobsParked.get(), deadlineMisses.get(),
                failures.get(), priorityBoosts.get(), queued, startLatencyTotal.copy(), executionTotal.copy());
    }

    private static long clamp(long valueNs) {
        return valueNs < 0 ? 0 : Math.min(valueNs, HIGHEST_TRACKABLE_NS);
    }

    /** Single writer: a release store is enough and cheaper than an atomic add. */
    private static void increment(AtomicLong counter) {
        counter.setRelease(counter.getPlain() + 1);
    }
}
