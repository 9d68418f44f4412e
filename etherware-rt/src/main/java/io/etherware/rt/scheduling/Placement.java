package io.etherware.rt.scheduling;

/**
 * A Job Placement Rule's decision for one job (paper Section IV-B: "the ID of a Dispatcher and
 * the value for an attribute that is used within a job queue of a Dispatcher"). Immutable.
 *
 * @param dispatcherId which dispatcher runs the job, 0..n-1 of the Thread Scheduling Rule
 * @param key          the job's place in that dispatcher's queue: smaller runs first, ties by
 *                     arrival; an absolute time in nanoseconds for deadline-like policies
 */
public record Placement(int dispatcherId, long key) {

    /**
     * Checks the dispatcher id; any key is valid.
     *
     * @throws IllegalArgumentException when {@code dispatcherId} is negative
     */
    public Placement {
        if (dispatcherId < 0) {
            throw new IllegalArgumentException("dispatcherId=" + dispatcherId + " must be >= 0");
        }
    }
}
