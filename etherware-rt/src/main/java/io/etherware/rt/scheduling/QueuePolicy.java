package io.etherware.rt.scheduling;

/**
 * How a dispatcher's queue orders its jobs, as far as schedulability analysis is concerned. A
 * {@link JobPlacementRule} states it per dispatcher; admission control picks the utilization bound
 * from it. Immutable.
 *
 * <p>Dispatchers are non-preemptive among their own jobs (a job runs to completion on its
 * dispatcher thread); preemption happens between dispatchers, by OS priority. The bounds below
 * are the classical preemptive ones: they ignore the blocking of up to one lower-priority job per
 * dispatcher, which a careful designer adds as a WCET margin.
 */
public enum QueuePolicy {
    /** Arrival order. Bound 1: necessary only, FIFO gives no deadline guarantee. */
    FIFO,
    /** Shorter period first: Liu and Layland's bound {@code n (2^(1/n) - 1)}. */
    RATE_MONOTONIC,
    /** Earlier absolute deadline first: bound 1. */
    EARLIEST_DEADLINE_FIRST;

    /**
     * The utilization up to which a number of periodic streams on one dispatcher is schedulable.
     *
     * @param streams how many streams the dispatcher runs
     * @return the bound: 1 for {@link #FIFO} and {@link #EARLIEST_DEADLINE_FIRST}; for
     *         {@link #RATE_MONOTONIC} {@code n (2^(1/n) - 1)}, 1 for at most one stream and falling
     *         towards ln 2 (about 0.693) as {@code streams} grows
     */
    public double utilizationBound(int streams) {
        if (this != RATE_MONOTONIC || streams <= 1) {
            return 1.0;
        }
        return streams * (Math.pow(2.0, 1.0 / streams) - 1.0);
    }
}
