package io.etherware.core.scheduler;

import io.etherware.core.time.NodeClock;
import java.util.Comparator;
import java.util.List;

/**
 * The dispatching mechanism of a node (paper Section IV-B): which thread delivers a job and in
 * what order. The kernel resolves profiles and guards components; a scheduler only orders and
 * runs jobs. {@link FifoScheduler} is the original Etherware's single dispatcher; the real-time
 * Dispatching Module lives in {@code etherware-rt}.
 *
 * <p>Lifecycle: {@link #start} once, then {@link #submit} from any thread, then
 * {@link #shutdown} once.
 */
public interface Scheduler {

    /** {@return a short name for logs and reports, e.g. {@code fifo}} */
    String name();

    /**
     * Starts the dispatcher threads.
     *
     * @param runner the kernel's delivery callback
     * @param clock  the node's clock; dispatchers read its monotonic time
     * @throws IllegalStateException if the scheduler was already started
     */
    void start(JobRunner runner, NodeClock clock);

    /**
     * Queues a job. Callable from any thread, including dispatcher threads; never blocks on
     * another job's execution.
     *
     * @param job the job to queue; one that comes back after waiting for its busy component is
     *            already placed and keeps that placement
     * @return false if the scheduler is shut down and did not take the job (the caller accounts
     *         for it); true otherwise
     */
    boolean submit(Job job);

    /**
     * The order of urgency among placed jobs, most urgent first. The kernel uses it to choose
     * which of the jobs waiting for a busy component goes next. The default is arrival order.
     *
     * @return a comparator of placed jobs that orders the more urgent first
     */
    default Comparator<Job> urgency() {
        return Comparator.comparingLong(Job::sequence);
    }

    /**
     * Stops taking jobs, lets the dispatchers drain their queues for at most {@code timeoutNs},
     * then stops the threads.
     *
     * @param timeoutNs how long the dispatchers may drain, in nanoseconds; &gt;= 0
     * @return the jobs that were queued but never run, so the kernel can count them as discarded
     */
    List<Job> shutdown(long timeoutNs);
}
