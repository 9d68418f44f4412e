package io.etherware.core.scheduler;

import io.etherware.core.message.Message;
import java.util.Objects;

/**
 * One delivery: a message on its way to one component (paper Section III-A: "an object, called
 * job, which contains the Message and the deliverable address of the receiver").
 *
 * <p>The kernel creates jobs; a {@link Scheduler} decides where and when each runs and hands it
 * back through {@link JobRunner#run}. A scheduler records its placement decision with
 * {@link #place(int, long)} before queueing the job; the placement is then fixed for the job's
 * life (a job that waits for its busy component is re-queued with the same placement, so its
 * order is kept).
 *
 * <p>Thread-safety: the immutable fields are safe everywhere. The placement is written once by
 * the scheduler on the submitting thread before the job is published to a queue, which makes it
 * visible to the dispatcher that takes it.
 */
public final class Job {

    private final Message message;
    private final String targetName;
    private final Object target;
    private final long sequence;
    private final long releaseNs;

    private int dispatcherId = -1;
    private long key;
    private boolean reserved;

    /**
     * A job for one delivery, not yet placed.
     *
     * @param message    what is delivered
     * @param targetName the receiving component's profile text, for accounting and logs
     * @param target     the kernel's handle of the receiver; opaque to schedulers
     * @param sequence   arrival order, unique and increasing within a node; ties are broken by it
     * @param releaseNs  when the job became ready, on the node's monotonic clock: the enqueue time,
     *                   or a Tick's scheduled release; start latency is measured from it
     */
    public Job(Message message, String targetName, Object target, long sequence, long releaseNs) {
        this.message = Objects.requireNonNull(message, "message");
        this.targetName = Objects.requireNonNull(targetName, "targetName");
        this.target = Objects.requireNonNull(target, "target");
        this.sequence = sequence;
        this.releaseNs = releaseNs;
    }

    /** {@return the message this job delivers} */
    public Message message() {
        return message;
    }

    /** {@return the receiving component's profile text, for accounting and logs} */
    public String targetName() {
        return targetName;
    }

    /** {@return the kernel's handle of the receiver} Schedulers must treat it as opaque. */
    public Object target() {
        return target;
    }

    /** {@return the arrival order, unique and increasing within a node; it breaks ties} */
    public long sequence() {
        return sequence;
    }

    /**
     * {@return when the job became ready, on the node's monotonic clock} Start latency and the
     * absolute deadline are measured from it.
     */
    public long releaseNs() {
        return releaseNs;
    }

    /**
     * {@return the absolute deadline on the monotonic clock, {@link #releaseNs()} plus the QoS
     * deadline, or {@link Long#MAX_VALUE} when the message's QoS has none}
     */
    public long absoluteDeadlineNs() {
        long deadlineNs = message.qos().deadlineNs();
        return deadlineNs > 0 ? releaseNs + deadlineNs : Long.MAX_VALUE;
    }

    /**
     * Records the scheduler's placement. Only the first call counts; re-queues keep it. Called on
     * the submitting thread before the job is queued.
     *
     * @param newDispatcherId the dispatcher that runs the job, &gt;= 0 (a negative id leaves the
     *                        job unplaced)
     * @param newKey          the ordering key within that dispatcher's queue; smaller runs first
     */
    public void place(int newDispatcherId, long newKey) {
        if (dispatcherId < 0) {
            dispatcherId = newDispatcherId;
            key = newKey;
        }
    }

    /** {@return whether {@link #place} was called} */
    public boolean isPlaced() {
        return dispatcherId >= 0;
    }

    /** {@return the dispatcher chosen by the scheduler, or -1 before placement} */
    public int dispatcherId() {
        return dispatcherId;
    }

    /** {@return the ordering key in the dispatcher's queue (smaller runs first), 0 if unplaced} */
    public long key() {
        return key;
    }

    /**
     * {@return whether the kernel has already reserved the receiving component for this job} It
     * waited for the component and is now next. Kernel use only.
     */
    public boolean isReserved() {
        return reserved;
    }

    /** Kernel use only: marks the job as holding its component's reservation. */
    public void reserve() {
        reserved = true;
    }

    @Override
    public String toString() {
        return "Job[" + message.messageId() + " -> " + targetName + ", seq=" + sequence
                + (dispatcherId >= 0 ? ", dispatcher=" + dispatcherId + ", key=" + key : "") + "]";
    }
}
