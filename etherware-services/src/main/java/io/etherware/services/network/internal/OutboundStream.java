package io.etherware.services.network.internal;

import java.util.ArrayDeque;
import java.util.List;

/**
 * This node's numbered stream of messages to a peer on one lane: the stream's id, the next
 * number, the messages written and not yet acknowledged (kept, with their encoding, to be sent
 * again on a new connection or reported lost) and how many the peer has acknowledged.
 *
 * <p>Locking: guarded by its {@link Link}'s lock; {@link #ackedCount} and {@link #unackedSinceNs}
 * are also read without it.
 */
final class OutboundStream {

    /**
     * On a link that carries every criticality (one lane), bytes of NONE and LOW messages written
     * to the peer and not yet acknowledged, at most (one larger message may go alone): a HIGH
     * message then waits behind at most this much LOW data in the sockets and the peer's reader,
     * instead of behind whatever the socket buffers hold (MiBs on loopback). The peer acknowledges
     * every 64 KiB it receives, so LOW throughput is kept. With two lanes, HIGH never shares a
     * connection with LOW and no such bound is needed.
     */
    static final int LOW_IN_FLIGHT_BYTES = 128 * 1024;

    /** Whether NONE and LOW messages in flight are bounded ({@link #LOW_IN_FLIGHT_BYTES}). */
    private final boolean boundsLow;
    /** Where a message is settled when it leaves the stream (acknowledged, refused, given up). */
    private final Generations generations;
    private final ArrayDeque<InFlight> inFlight = new ArrayDeque<>();
    private long streamId = NetworkContext.newStreamId();
    private long nextSeq;
    /** Bytes of the messages in flight. */
    private long inFlightBytes;
    /** Bytes of the NONE and LOW messages in flight. */
    private long lowInFlightBytes;
    private volatile long ackedCount;
    /** Since when something written is unacknowledged with no acknowledgement progress; 0: nothing. */
    private volatile long unackedSinceNs;

    OutboundStream(boolean boundsLow, Generations generations) {
        this.boundsLow = boundsLow;
        this.generations = generations;
    }

    long streamId() {
        return streamId;
    }

    /** The number the next message gets: how many were numbered in this stream. */
    long nextSeq() {
        return nextSeq;
    }

    /** How many messages of the stream the peer has acknowledged. */
    long ackedCount() {
        return ackedCount;
    }

    /** Since when something is unacknowledged with no acknowledgement progress; 0 when nothing is. */
    long unackedSinceNs() {
        return unackedSinceNs;
    }

    int size() {
        return inFlight.size();
    }

    boolean isEmpty() {
        return inFlight.isEmpty();
    }

    /** Bytes of the messages in flight. */
    long bytes() {
        return inFlightBytes;
    }

    /** Whether NONE or LOW messages are in flight. */
    boolean hasLowInFlight() {
        return lowInFlightBytes > 0;
    }

    /** The messages written and not acknowledged, in stream order. */
    List<InFlight> unacknowledged() {
        return List.copyOf(inFlight);
    }

    /** Numbers {@code outgoing} and keeps it until the peer acknowledges it. */
    InFlight add(Outgoing outgoing) {
        if (inFlight.isEmpty()) {
            unackedSinceNs = NetworkContext.nowNs(); // the not-reading clock starts
        }
        var entry = new InFlight(nextSeq++, outgoing, outgoing.xml());
        inFlight.addLast(entry);
        inFlightBytes += entry.xml().length;
        if (entry.outgoing().isSheddable()) {
            lowInFlightBytes += entry.xml().length;
        }
        return entry;
    }

    /** Whether {@code next} may go now, with {@code chosen} more LOW bytes already taken. */
    boolean lowRoomFor(Outgoing next, long chosen) {
        if (!boundsLow || !next.isSheddable()) {
            return true;
        }
        long already = lowInFlightBytes + chosen;
        return already == 0 || already + next.xml().length <= LOW_IN_FLIGHT_BYTES;
    }

    /**
     * Why the peer's claim (RESUME) to have {@code receivedCount} messages of this stream cannot
     * be taken, or null: more than were sent, or fewer than it acknowledged (those were released
     * and cannot be sent again, so resuming would leave a gap the peer never gets past).
     */
    String resumeRefusal(long receivedCount) {
        if (receivedCount > nextSeq) {
            return "the peer claims " + receivedCount + " messages of stream " + Long.toHexString(streamId)
                    + ", only " + nextSeq + " were sent";
        }
        if (receivedCount < ackedCount) {
            return "the peer claims " + receivedCount + " messages of stream " + Long.toHexString(streamId)
                    + ", but had acknowledged " + ackedCount;
        }
        return null;
    }

    /** Why an acknowledgement of {@code count} contradicts the stream, or null. */
    String ackContradiction(long count) {
        if (count > nextSeq) {
            return "acknowledgement of " + count + " messages, only " + nextSeq + " were sent";
        }
        if (count < ackedCount) {
            // Acknowledgements are cumulative: one that goes back contradicts what was released.
            return "acknowledgement of " + count + " messages after " + ackedCount + " were acknowledged";
        }
        return null;
    }

    /** The peer's kernel has the first {@code count} messages: they are released. */
    void acknowledge(long count) {
        boolean released = false;
        while (!inFlight.isEmpty() && inFlight.peekFirst().seq() < count) {
            removed(inFlight.pollFirst());
            released = true;
        }
        if (inFlight.isEmpty()) {
            unackedSinceNs = 0;
        } else if (released) {
            unackedSinceNs = NetworkContext.nowNs();
        }
        ackedCount = Math.max(ackedCount, count);
    }

    /** The peer refused message {@code seq}: no longer kept; returns it, or null if it was not. */
    InFlight remove(long seq) {
        var each = inFlight.iterator();
        while (each.hasNext()) {
            InFlight entry = each.next();
            if (entry.seq() == seq) {
                each.remove();
                removed(entry);
                return entry;
            }
        }
        return null;
    }

    /**
     * The peer does not know this stream (it restarted): numbering starts again at 0 under the same
     * id, which the peer adopts from our RESUME; returns the unacknowledged, of unknown fate.
     */
    List<InFlight> restartNumbering() {
        List<InFlight> lost = List.copyOf(inFlight);
        for (InFlight entry : lost) {
            generations.settle(entry.outgoing().generation());
        }
        inFlight.clear();
        inFlightBytes = 0;
        lowInFlightBytes = 0;
        unackedSinceNs = 0;
        nextSeq = 0;
        ackedCount = 0;
        return lost;
    }

    /**
     * Starts the stream afresh under a new id (the peer, when it sees the id, must not expect the
     * old numbers); returns the unacknowledged, of unknown fate.
     */
    List<InFlight> reset() {
        List<InFlight> lost = restartNumbering();
        streamId = NetworkContext.newStreamId();
        return lost;
    }

    /** A new connection carries the stream on: the not-reading clock starts now if anything waits. */
    void restartClock() {
        unackedSinceNs = inFlight.isEmpty() ? 0 : NetworkContext.nowNs();
    }

    private void removed(InFlight entry) {
        generations.settle(entry.outgoing().generation());
        inFlightBytes -= entry.xml().length;
        if (entry.outgoing().isSheddable()) {
            lowInFlightBytes -= entry.xml().length;
        }
    }
}
