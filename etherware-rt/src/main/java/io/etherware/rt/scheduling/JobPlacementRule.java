package io.etherware.rt.scheduling;

import io.etherware.core.scheduler.Job;

/**
 * The Job Placement Rule (JPR) of paper Section IV-B: the scheduling policy, as a replaceable
 * object. Given a job and the time, it says which dispatcher runs it and where in that
 * dispatcher's queue it goes. The dispatching mechanism never changes with the policy.
 *
 * <p>Shipped: {@link CriticalityDeadlinePlacement} (Algorithm 1, the default),
 * {@link RateMonotonicPlacement}, {@link EdfPlacement}, {@link FifoPlacement}.
 *
 * <p>Threading contract: {@link #place} is called on the submitting thread (any thread, including
 * dispatcher threads), concurrently; it must be thread-safe, fast, allocation-light and must not
 * block. It is called once per job: a job that already has a placement (a parked job coming back)
 * keeps it.
 */
public interface JobPlacementRule {

    /**
     * Places one job.
     *
     * @param job   the job, not yet placed
     * @param nowNs the scheduler's reading of the node's monotonic clock at submission
     * @return the dispatcher, in [0, {@link #dispatchersRequired()}), and the queue key
     */
    Placement place(Job job, long nowNs);

    /**
     * How many dispatchers this rule needs; the scheduler's configuration checks it against the TSR.
     *
     * @return the highest dispatcher id this rule places on, plus one
     */
    int dispatchersRequired();

    /**
     * How the keys this rule gives order one dispatcher's queue, for admission control.
     *
     * @param dispatcherId a dispatcher, in [0, {@link #dispatchersRequired()})
     * @return the queue policy, which picks the utilization bound
     */
    QueuePolicy queuePolicy(int dispatcherId);

    /**
     * A short name for logs and reports.
     *
     * @return e.g. {@code criticality-deadline}
     */
    String name();
}
