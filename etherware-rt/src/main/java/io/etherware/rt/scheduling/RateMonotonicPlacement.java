package io.etherware.rt.scheduling;

import io.etherware.core.message.QoS;
import io.etherware.core.scheduler.Job;
import java.util.Arrays;

/**
 * Rate-monotonic placement: the shorter a job's period, the sooner it runs (key = period, ties by
 * arrival). Jobs without a period go to dispatcher 0 in arrival order.
 *
 * <p>By default every periodic job goes to dispatcher 1 (non-preemptive rate-monotonic within one
 * real-time dispatcher). With {@link #banded(long...)}, periods are split into bands that map to
 * dispatchers 1, 2, ... so that a short-period band preempts a long-period one through the OS
 * priorities of the Thread Scheduling Rule. Immutable and thread-safe.
 */
public final class RateMonotonicPlacement implements JobPlacementRule {

    private final long[] bandUpperBoundsNs;

    /** All periodic jobs on dispatcher 1. */
    public RateMonotonicPlacement() {
        this.bandUpperBoundsNs = new long[0];
    }

    private RateMonotonicPlacement(long[] bandUpperBoundsNs) {
        this.bandUpperBoundsNs = bandUpperBoundsNs;
    }

    /**
     * Periods up to {@code periodUpperBoundsNs[0]} on dispatcher 1, up to {@code [1]} on dispatcher
     * 2, and so on; longer periods on the dispatcher after the last bound. Bounds must be positive
     * and strictly ascending.
     *
     * @param periodUpperBoundsNs the bands' inclusive upper period bounds in nanoseconds, positive
     *                            and strictly ascending; none is the same as the default placement
     * @return the placement; it needs {@code periodUpperBoundsNs.length + 2} dispatchers
     * @throws IllegalArgumentException when a bound is not positive or the bounds do not ascend
     */
    public static RateMonotonicPlacement banded(long... periodUpperBoundsNs) {
        long[] bounds = periodUpperBoundsNs.clone();
        for (int i = 0; i < bounds.length; i++) {
            if (bounds[i] <= 0 || (i > 0 && bounds[i] <= bounds[i - 1])) {
                throw new IllegalArgumentException("periodUpperBoundsNs=" + Arrays.toString(bounds)
                        + " must be positive and strictly ascending");
            }
        }
        return new RateMonotonicPlacement(bounds);
    }

    @Override
    public Placement place(Job job, long nowNs) {
        QoS qos = job.message().qos();
        if (!qos.hasPeriod()) {
            return new Placement(0, nowNs);
        }
        int band = 0;
        while (band < bandUpperBoundsNs.length && qos.periodNs() > bandUpperBoundsNs[band]) {
            band++;
        }
        return new Placement(1 + band, qos.periodNs());
    }

    @Override
    public int dispatchersRequired() {
        return 2 + bandUpperBoundsNs.length;
    }

    @Override
    public QueuePolicy queuePolicy(int dispatcherId) {
        return dispatcherId == 0 ? QueuePolicy.FIFO : QueuePolicy.RATE_MONOTONIC;
    }

    @Override
    public String name() {
        return "rate-monotonic";
    }

    @Override
    public String toString() {
        return bandUpperBoundsNs.length == 0 ? name() : name() + Arrays.toString(bandUpperBoundsNs);
    }
}
