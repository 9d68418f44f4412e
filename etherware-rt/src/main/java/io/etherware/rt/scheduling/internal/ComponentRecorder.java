package io.etherware.rt.scheduling.internal;

import io.etherware.rt.scheduling.ComponentStats;
import java.util.concurrent.atomic.AtomicLong;

/**
 * One component's counters. Its jobs may run on several dispatchers (one at a time), so the
 * counters are atomic; uncontended in practice. Thread-safe.
 */
public final class ComponentRecorder {

    private final AtomicLong jobsRun = new AtomicLong();
    private final AtomicLong deadlineMisses = new AtomicLong();
    private final AtomicLong totalExecutionNs = new AtomicLong();
    private final AtomicLong maxExecutionNs = new AtomicLong();

    void recordRun(long executionNs, boolean missed) {
        jobsRun.incrementAndGet();
        totalExecutionNs.addAndGet(executionNs);
        long max = maxExecutionNs.get();
        while (executionNs > max && !maxExecutionNs.compareAndSet(max, executionNs)) {
            max = maxExecutionNs.get();
        }
        if (missed) {
            deadlineMisses.incrementAndGet();
        }
    }

    public ComponentStats snapshot(String component) {
        return new ComponentStats(component, jobsRun.get(), deadlineMisses.get(), totalExecutionNs.get(),
                maxExecutionNs.get());
    }
}
