package io.etherware.core.scheduler;

import io.etherware.core.message.Message;
import java.lang.invoke.MethodHandles;
import java.lang.invoke.VarHandle;
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
 * <p><b>Reuse.</b> The kernel takes its jobs from a pool of the sending thread ({@link #pooled}), so
 * that a send allocates nothing in steady state. A scheduler hands a job back with
 * {@link #recycle()} once it has run ({@link JobRunner#run} returned true) and the scheduler holds
 * no reference to it any more; the job may then carry another delivery. So neither a scheduler nor
 * a {@code JobPlacementRule} may keep a job beyond that point: copy what is needed (as
 * {@code DeadlineMiss} does). A job that is never recycled (refused, discarded at shutdown, or
 * run by a scheduler that does not recycle) is left to the garbage collector, which is always safe.
 *
 * <p>Thread-safety: a job's delivery fields are written by the thread that makes or takes it from
 * the pool, before it is submitted; the placement is written once by the scheduler on the
 * submitting thread before the job is published to a queue. The queue's publication makes both
 * visible to the dispatcher that takes it. {@link #link} is the scheduler's, used under the same
 * publication.
 */
public final class Job {

    private Message message;
    private String targetName;
    private Object target;
    private long sequence;
    private long releaseNs;

    private int dispatcherId = -1;
    private long key;
    private boolean reserved;
    /** The next job in a scheduler's intrusive queue, or null. */
    private Job link;
    /** The pool this job returns to, or null for a job made with the constructor. */
    private final JobPool pool;
    /** The next job in {@link #pool}'s free or returned list; the pool's. */
    Job poolNext;
    /** This job's depth in the pool's returned list (1 at the bottom); the pool's. */
    int poolDepth;

    private static final VarHandle MESSAGE;

    static {
        try {
            MESSAGE = MethodHandles.lookup().findVarHandle(Job.class, "message", Message.class);
        } catch (ReflectiveOperationException e) {
            throw new ExceptionInInitializerError(e);
        }
    }

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
        this((JobPool) null);
        set(message, targetName, target, sequence, releaseNs);
    }

    /** An empty job of {@code pool}, filled by {@link #set} before use. */
    Job(JobPool pool) {
        this.pool = pool;
    }

    /**
     * A job for one delivery, not yet placed, taken from the calling thread's pool of recycled
     * jobs when it has one (no allocation), else made. The same as the constructor otherwise.
     *
     * @param message    what is delivered
     * @param targetName the receiving component's profile text, for accounting and logs
     * @param target     the kernel's handle of the receiver; opaque to schedulers
     * @param sequence   arrival order, unique and increasing within a node
     * @param releaseNs  when the job became ready, on the node's monotonic clock
     * @return a job that is not placed, not reserved and in no queue
     */
    public static Job pooled(Message message, String targetName, Object target, long sequence, long releaseNs) {
        Job job = JobPool.take();
        job.set(message, targetName, target, sequence, releaseNs);
        return job;
    }

    private void set(Message newMessage, String newTargetName, Object newTarget, long newSequence, long newReleaseNs) {
        this.targetName = Objects.requireNonNull(newTargetName, "targetName");
        this.target = Objects.requireNonNull(newTarget, "target");
        this.sequence = newSequence;
        this.releaseNs = newReleaseNs;
        // Cleared by the recycler too; again here, on the thread that fills the job, so that a
        // reused job never carries an old placement, reservation or link.
        this.dispatcherId = -1;
        this.key = 0;
        this.reserved = false;
        this.link = null;
        this.message = Objects.requireNonNull(newMessage, "message");
    }

    /**
     * Hands the job back for reuse: called by a scheduler once the job has run and it keeps no
     * reference to it. A pooled job is cleared (so the pool holds no message) and returned to the
     * pool of the thread that took it, and must not be used afterwards; a job made with the
     * constructor is left as it is, to the garbage collector. Lock-free and allocation-free, from
     * any thread.
     *
     * @throws IllegalStateException when a pooled job was recycled already, even by two threads at
     *                               once (a scheduler's bug; the pool is left intact)
     */
    public void recycle() {
        if (pool == null) {
            return;
        }
        Message delivered = message;
        // One CAS: of two recycles of the same job, at most one gives it back.
        if (delivered == null || !MESSAGE.compareAndSet(this, delivered, (Message) null)) {
            throw new IllegalStateException("job recycled twice");
        }
        targetName = null;
        target = null;
        dispatcherId = -1;
        key = 0;
        reserved = false;
        link = null;
        pool.giveBack(this);
    }

    /**
     * {@return the next job in the scheduler queue this job is in, or null} For a scheduler that
     * chains its queued jobs through the jobs themselves, so queueing allocates nothing; a job is
     * in at most one such queue at a time.
     */
    public Job link() {
        return link;
    }

    /**
     * Sets the scheduler's link (see {@link #link()}). Written before the job is published to the
     * queue, and read by the thread that takes it.
     *
     * @param next the next job in the queue, or null
     */
    public void link(Job next) {
        link = next;
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
