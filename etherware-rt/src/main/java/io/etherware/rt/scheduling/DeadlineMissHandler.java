package io.etherware.rt.scheduling;

/**
 * Called when a job completes after its deadline, like RTSJ's deadline-miss handler: to degrade,
 * alarm or switch a controller to a safe mode.
 *
 * <p>Threading contract: called on the dispatcher thread that ran the late job, right after it
 * completed and before that dispatcher takes its next job, at that dispatcher's priority. It must
 * be short and must not block; hand real work to a component by sending a message. An exception it
 * throws is logged and counted as a failure, never kills the dispatcher.
 */
@FunctionalInterface
public interface DeadlineMissHandler {

    /** Does nothing; misses are still counted and recorded. */
    DeadlineMissHandler NONE = miss -> { };

    /**
     * Reacts to one late job, on the dispatcher thread that ran it; must be short and must not block.
     *
     * @param miss the late job: its dispatcher, component, message and times
     */
    void onDeadlineMiss(DeadlineMiss miss);
}
