package io.etherware.rt.scheduling;

import io.etherware.core.message.Criticality;
import io.etherware.core.message.MessageId;

/**
 * A job that completed after its absolute deadline.
 * Immutable; built on the dispatcher thread that ran the job.
 *
 * @param dispatcherId which dispatcher ran it
 * @param component    the receiving component's profile text
 * @param messageId    the late message
 * @param criticality  its criticality
 * @param releaseNs    when it was released (monotonic clock)
 * @param startNs      when its dispatcher started it
 * @param completionNs when it completed
 * @param deadlineNs   its absolute deadline
 */
public record DeadlineMiss(int dispatcherId, String component, MessageId messageId, Criticality criticality,
                           long releaseNs, long startNs, long completionNs, long deadlineNs) {

    /**
     * How late the job completed.
     *
     * @return {@code completionNs - deadlineNs}, in nanoseconds, always positive
     */
    public long latenessNs() {
        return completionNs - deadlineNs;
    }
}
