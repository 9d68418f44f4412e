package io.etherware.rt.scheduling;

/**
 * A snapshot of one component's time accounting since the scheduler started, over all dispatchers.
 * Immutable.
 *
 * @param component        the component's profile text ({@code Job.targetName()})
 * @param jobsRun          jobs run to completion
 * @param deadlineMisses   jobs that completed after their deadline
 * @param totalExecutionNs sum of execution times
 * @param maxExecutionNs   longest execution time seen: a lower bound for the component's WCET
 */
public record ComponentStats(String component, long jobsRun, long deadlineMisses, long totalExecutionNs,
                             long maxExecutionNs) {
}
