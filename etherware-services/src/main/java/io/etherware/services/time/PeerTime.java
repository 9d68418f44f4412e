package io.etherware.services.time;

/**
 * What this node knows of one peer's clock: the estimated offset (peer clock minus local clock)
 * at a local instant, how fast it changes, and how sure the estimate is.
 *
 * <p>Immutable; a snapshot.
 *
 * @param nodeId        the peer
 * @param offsetNs      peer epoch clock minus local epoch clock at {@code atEpochNs}
 * @param atEpochNs     the local epoch time the offset refers to
 * @param driftPpm      the rate at which the offset changes, parts per million (the peer clock
 *                      runs fast when positive); 0 until enough exchanges span a long enough time
 * @param roundTripNs   the round trip of the best (minimum-delay) exchange in the window, or -1
 *                      before the first exchange
 * @param uncertaintyNs half that round trip: the bound on the offset's error from asymmetric
 *                      paths; -1 before the first exchange, when the offset is a guess from the
 *                      handshake
 * @param samples       exchanges in the window
 */
public record PeerTime(String nodeId, long offsetNs, long atEpochNs, double driftPpm, long roundTripNs,
                       long uncertaintyNs, int samples) {

    /**
     * The estimated offset at local epoch time {@code localEpochNs}, extrapolated with the drift.
     *
     * @param localEpochNs a time of this node's epoch clock, in nanoseconds
     * @return peer epoch clock minus local epoch clock at that time, in nanoseconds
     */
    public long offsetAt(long localEpochNs) {
        return offsetNs + Math.round(driftPpm * 1e-6 * (localEpochNs - atEpochNs));
    }

    /**
     * Whether at least one exchange has been measured.
     *
     * @return true if {@code samples > 0}; false while the offset is the handshake's guess
     */
    public boolean isMeasured() {
        return samples > 0;
    }
}
