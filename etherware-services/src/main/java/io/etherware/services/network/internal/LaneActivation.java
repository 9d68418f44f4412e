package io.etherware.services.network.internal;

import java.util.List;

/**
 * The outcome of {@link Link#activate}: whether the candidate connection now carries its lane.
 *
 * @param accepted whether the candidate is the lane's connection now
 * @param loser    accepted: the connection it replaced, to close, or null; refused: the candidate
 * @param lost     messages of this node's stream of unknown fate, to report to their senders
 * @param refusal  why the connection is refused for a protocol error, or null (a duplicate, or
 *                 the messenger closes)
 */
record LaneActivation(boolean accepted, Connection loser, List<InFlight> lost, String refusal) {
}
