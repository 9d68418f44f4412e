package io.etherware.core.scheduler;

/**
 * The kernel side of dispatching: a scheduler's dispatcher thread calls {@link #run} for each job
 * it takes from its queue.
 */
@FunctionalInterface
public interface JobRunner {

    /**
     * Delivers {@code job} to its component on the calling dispatcher thread, if the component is
     * free. If the component is busy with another message on another dispatcher (design decision
     * 3: one message at a time per component), the job is parked with the component instead, and
     * the kernel hands it back through {@link Scheduler#submit} as soon as the component is free
     * and this job is the most urgent one waiting for it; the dispatcher moves on at once.
     *
     * <p>Never throws for a component's failure: that goes to supervision.
     *
     * @param job   the job taken from the queue
     * @param nowNs the dispatcher's reading of the monotonic clock when it took the job
     * @return whether the job ran now ({@code false}: parked, it will come back)
     */
    boolean run(Job job, long nowNs);

    /**
     * The id of the node whose jobs these are. Schedulers add it to their thread names
     * ({@code rt-dispatcher-1@plant}) and log lines, so that two nodes in one JVM can be told apart.
     *
     * @return the node id; empty (the default) for a runner that belongs to no node
     */
    default String nodeId() {
        return "";
    }
}
