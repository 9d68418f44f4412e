package io.etherware.rt.scheduling;

import io.etherware.rt.stats.LatencySnapshot;

/**
 * A snapshot of one dispatcher's time accounting since the scheduler started. Immutable.
 *
 * <p>The latency distributions are in nanoseconds, with 2 significant digits (values within 1 %),
 * up to 60 s (longer values are recorded as 60 s).
 *
 * @param dispatcherId     the dispatcher
 * @param jobsRun          jobs its thread ran to completion (parked jobs not included)
 * @param jobsParked       jobs it handed back because their component was busy elsewhere
 * @param deadlineMisses   jobs with a deadline that completed after it
 * @param failures         jobs whose runner or miss handler threw (a kernel bug; components'
 *                         exceptions go to supervision, not here)
 * @param priorityBoosts   times its thread was raised to a waiting job's priority (priority
 *                         inheritance)
 * @param queuedJobs       jobs waiting in its queue at the time of the snapshot (approximate)
 * @param startLatencyNs   release to start of run, per job run
 * @param executionNs      start to completion, per job run
 */
public record DispatcherStats(int dispatcherId, long jobsRun, long jobsParked, long deadlineMisses, long failures,
                              long priorityBoosts, long queuedJobs, LatencySnapshot startLatencyNs,
                              LatencySnapshot executionNs) {
}
