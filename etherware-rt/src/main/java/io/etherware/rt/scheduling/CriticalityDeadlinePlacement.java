package io.etherware.rt.scheduling;

import io.etherware.core.message.QoS;
import io.etherware.core.scheduler.Job;
import io.etherware.rt.scheduling.internal.Keys;

/**
 * The paper's Algorithm 1, exactly: HIGH criticality to dispatcher 1, MIDDLE to 2, LOW to 3, each
 * with the key {@code now + period} (the job's implicit deadline when its deadline equals its
 * period, so each real-time dispatcher runs earliest-implicit-deadline first). Messages without
 * QoS ({@code Criticality.NONE}) go to dispatcher 0, the non-real-time one, in arrival order
 * (key = now; Algorithm 1 does not place them).
 *
 * <p>Needs four dispatchers, as in {@link ThreadSchedulingRule#tableII()}. A job without a period
 * gets {@code now} as its key, so it runs before periodic jobs released at the same time.
 * Stateless and thread-safe.
 */
public final class CriticalityDeadlinePlacement implements JobPlacementRule {

    /** The dispatcher of messages without QoS. */
    public static final int NON_REALTIME_DISPATCHER = 0;
    /** The dispatcher of HIGH messages: SCHED_FIFO {@value ThreadSchedulingRule#HIGH_PRIORITY} in Table II. */
    public static final int HIGH_DISPATCHER = 1;
    /** The dispatcher of MIDDLE messages: SCHED_FIFO {@value ThreadSchedulingRule#MIDDLE_PRIORITY} in Table II. */
    public static final int MIDDLE_DISPATCHER = 2;
    /** The dispatcher of LOW messages: SCHED_FIFO {@value ThreadSchedulingRule#LOW_PRIORITY} in Table II. */
    public static final int LOW_DISPATCHER = 3;

    /** The rule; it holds no state, so one instance may serve any number of schedulers. */
    public CriticalityDeadlinePlacement() {
    }

    @Override
    public Placement place(Job job, long nowNs) {
        QoS qos = job.message().qos();
        return switch (qos.criticality()) {
            case HIGH -> new Placement(HIGH_DISPATCHER, Keys.saturatedAdd(nowNs, qos.periodNs()));
            case MIDDLE -> new Placement(MIDDLE_DISPATCHER, Keys.saturatedAdd(nowNs, qos.periodNs()));
            case LOW -> new Placement(LOW_DISPATCHER, Keys.saturatedAdd(nowNs, qos.periodNs()));
            case NONE -> new Placement(NON_REALTIME_DISPATCHER, nowNs);
        };
    }

    @Override
    public int dispatchersRequired() {
        return 4;
    }

    @Override
    public QueuePolicy queuePolicy(int dispatcherId) {
        return dispatcherId == NON_REALTIME_DISPATCHER ? QueuePolicy.FIFO : QueuePolicy.EARLIEST_DEADLINE_FIRST;
    }

    @Override
    public String name() {
        return "criticality-deadline";
    }

    @Override
    public String toString() {
        return name();
    }
}
