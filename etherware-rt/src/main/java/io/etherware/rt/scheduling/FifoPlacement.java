package io.etherware.rt.scheduling;

import io.etherware.core.scheduler.Job;

/**
 * Arrival order on one dispatcher (0 by default), whatever the QoS: the original Etherware's
 * behaviour, useful as a baseline inside the same Dispatching Module. Immutable and thread-safe.
 */
public final class FifoPlacement implements JobPlacementRule {

    private final int dispatcherId;

    /** Everything on dispatcher 0. */
    public FifoPlacement() {
        this(0);
    }

    /**
     * Everything on one dispatcher.
     *
     * @param dispatcherId the dispatcher, at least 0
     * @throws IllegalArgumentException when {@code dispatcherId} is negative
     */
    public FifoPlacement(int dispatcherId) {
        if (dispatcherId < 0) {
            throw new IllegalArgumentException("dispatcherId=" + dispatcherId + " must be >= 0");
        }
        this.dispatcherId = dispatcherId;
    }

    /** Key 0 for every job, so the queue orders by arrival sequence alone. */
    @Override
    public Placement place(Job job, long nowNs) {
        return new Placement(dispatcherId, 0);
    }

    @Override
    public int dispatchersRequired() {
        return dispatcherId + 1;
    }

    @Override
    public QueuePolicy queuePolicy(int id) {
        return QueuePolicy.FIFO;
    }

    @Override
    public String name() {
        return "fifo";
    }

    @Override
    public String toString() {
        return name() + "(dispatcher " + dispatcherId + ")";
    }
}
