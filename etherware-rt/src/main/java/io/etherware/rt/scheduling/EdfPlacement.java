package io.etherware.rt.scheduling;

import io.etherware.core.scheduler.Job;

/**
 * Non-preemptive earliest-deadline-first placement: every job with a deadline goes to one
 * real-time dispatcher (1 by default) with its absolute deadline as key; jobs without a deadline
 * go to dispatcher 0 in arrival order. A running job is never preempted by an earlier deadline on
 * the same dispatcher, so a job may wait for at most one job already running. Immutable and
 * thread-safe.
 */
public final class EdfPlacement implements JobPlacementRule {

    private final int deadlineDispatcherId;

    /** Deadline jobs on dispatcher 1. */
    public EdfPlacement() {
        this(1);
    }

    /**
     * Deadline jobs on a given dispatcher.
     *
     * @param deadlineDispatcherId the dispatcher of jobs with a deadline, at least 1 (dispatcher 0
     *                             takes the others)
     * @throws IllegalArgumentException when {@code deadlineDispatcherId} is below 1
     */
    public EdfPlacement(int deadlineDispatcherId) {
        if (deadlineDispatcherId < 1) {
            throw new IllegalArgumentException("deadlineDispatcherId=" + deadlineDispatcherId
                    + " must be >= 1 (dispatcher 0 runs the jobs without a deadline)");
        }
        this.deadlineDispatcherId = deadlineDispatcherId;
    }

    @Override
    public Placement place(Job job, long nowNs) {
        long deadlineNs = job.absoluteDeadlineNs();
        return deadlineNs == Long.MAX_VALUE ? new Placement(0, nowNs) : new Placement(deadlineDispatcherId, deadlineNs);
    }

    @Override
    public int dispatchersRequired() {
        return deadlineDispatcherId + 1;
    }

    @Override
    public QueuePolicy queuePolicy(int dispatcherId) {
        return dispatcherId == deadlineDispatcherId ? QueuePolicy.EARLIEST_DEADLINE_FIRST : QueuePolicy.FIFO;
    }

    @Override
    public String name() {
        return "edf";
    }

    @Override
    public String toString() {
        return name() + "(dispatcher " + deadlineDispatcherId + ")";
    }
}
