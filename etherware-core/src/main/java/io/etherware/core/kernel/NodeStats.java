package io.etherware.core.kernel;

/**
 * Counters of a node, read at one moment (each counter is exact; they are not read atomically
 * together).
 *
 * @param nodeId          the node
 * @param jobs            jobs created: one per local delivery, plus one per reply or timeout
 *                        handed to a requesting component
 * @param handled         messages handled without an exception, all components ever added
 * @param failed          messages whose handling threw
 * @param restarts        restarts applied by components' restart policies
 * @param undeliverable   messages that could not be delivered (no match, ambiguous query,
 *                        stopped or failed component, failing route); senders were told
 * @param discarded       jobs dropped because the node was closing: queued at close beyond the
 *                        drain timeout, or sent after the scheduler stopped
 * @param requestTimeouts requests that got no reply in time
 * @param lateReplies     replies that came after their request had timed out, dropped
 * @param escalations     failures past a component's restart intensity
 * @param resets          node-wide resets of all components
 */
public record NodeStats(String nodeId, long jobs, long handled, long failed, long restarts, long undeliverable,
                        long discarded, long requestTimeouts, long lateReplies, long escalations, long resets) {
}
