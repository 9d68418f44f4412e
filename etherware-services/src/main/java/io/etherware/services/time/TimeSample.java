package io.etherware.services.time;

/**
 * One NTP-style four-timestamp exchange with a peer (RFC 5905 Section 8), all in epoch
 * nanoseconds: {@code t1} request sent and {@code t4} reply received on the local clock,
 * {@code t2} request received and {@code t3} reply sent on the peer's clock.
 *
 * <p>Immutable.
 *
 * @param t1 local clock when the request left
 * @param t2 peer clock when the request arrived
 * @param t3 peer clock when the reply left
 * @param t4 local clock when the reply arrived
 */
public record TimeSample(long t1, long t2, long t3, long t4) {

    /**
     * The peer's clock minus the local clock, assuming the two directions took equally long:
     * {@code ((t2 - t1) + (t3 - t4)) / 2}. Its error is at most half the {@link #roundTripNs()}.
     *
     * @return the offset in nanoseconds (positive: the peer's clock is ahead)
     */
    public long offsetNs() {
        return Math.floorDiv((t2 - t1) + (t3 - t4), 2);
    }

    /**
     * Time on the wire, both ways: {@code (t4 - t1) - (t3 - t2)}.
     *
     * @return the round trip in nanoseconds, without the peer's turnaround; negative only if a
     *         clock stepped during the exchange
     */
    public long roundTripNs() {
        return (t4 - t1) - (t3 - t2);
    }

    /**
     * The local time the offset refers to: midway between sending and receiving.
     *
     * @return {@code t1 + (t4 - t1) / 2}, local epoch nanoseconds
     */
    public long localMidpointNs() {
        return t1 + Math.floorDiv(t4 - t1, 2);
    }
}
