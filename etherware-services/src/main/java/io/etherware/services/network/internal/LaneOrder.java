package io.etherware.services.network.internal;

import java.util.concurrent.TimeUnit;

/**
 * The one order kept across a peer's lanes (NETWORK-PROTOCOL.md, "Priority on the wire"): a NONE
 * message of lane 1 goes after every message queued for the peer before it, on lane 0 too. Each
 * lane numbers its messages by {@link Generations}; lane 1's order knows lane 0's (its
 * precedent), and a NONE message waits until lane 0 settled the generation it closed. Lane 0 keeps
 * the generation such a message waits for, so that its writer asks the peer for an acknowledgement
 * at once (a SYNC) rather than the peer's delayed one.
 *
 * <p>Locking: owned by one {@link Link} and changed under that link's lock; {@link #hasSettled}
 * takes no lock (a volatile read), so lane 1 asks lane 0's order without touching lane 0's lock.
 */
final class LaneOrder {

    /** How often a writer looks again at a NONE message held for lane 0. */
    private static final long BARRIER_POLL_NS = TimeUnit.MILLISECONDS.toNanos(1);

    /** This lane's unsettled messages by generation. */
    private final Generations generations;
    /** Lane 0's order, whose earlier messages a NONE message of this lane waits for; null on lane 0. */
    private final LaneOrder precedent;
    /** The latest generation a NONE message of lane 1 waits for, until settled; -1: none. */
    private long syncUpTo = -1;

    /**
     * @param generations this lane's generations, also settled by its {@link OutboundStream}
     * @param precedent   lane 0's order on lane 1, else null
     */
    LaneOrder(Generations generations, LaneOrder precedent) {
        this.generations = generations;
        this.precedent = precedent;
    }

    /** A message is taken for this lane: returns its generation (lock held). */
    long take() {
        return generations.take();
    }

    /** Whether a NONE message waiting for lane 0 may go (lock held). */
    boolean mayGo(Outgoing next) {
        return next.after() < 0 || precedent == null || precedent.hasSettled(next.after());
    }

    /** {@code outgoing} leaves this lane for good without having been written (lock held). */
    void settle(Outgoing outgoing) {
        generations.settle(outgoing.generation());
    }

    /** Whether every message of {@code generation} and before is settled here. Lock-free. */
    boolean hasSettled(long generation) {
        return generations.settledUpTo(generation);
    }

    /** Closes this lane's open generation for a NONE message of lane 1 and returns it (lock held). */
    long close() {
        return generations.close();
    }

    /**
     * Whether the messages of {@code closed} still wait for the peer's acknowledgement, which it
     * may put off for up to 10 ms: if so, the writer is to follow them with a SYNC (lock held).
     */
    boolean awaitSync(long closed) {
        if (generations.settledUpTo(closed)) {
            return false;
        }
        syncUpTo = closed;
        return true;
    }

    /**
     * Whether a writer's turn that {@code carriesMessages} is to end with a SYNC: more of what a
     * NONE message of lane 1 waits for goes out now (lock held).
     */
    boolean syncAfter(boolean carriesMessages) {
        if (syncUpTo < 0) {
            return false;
        }
        if (generations.settledUpTo(syncUpTo)) {
            syncUpTo = -1;
            return false;
        }
        return carriesMessages;
    }

    /**
     * How long a writer with nothing to send waits, at most, for its heartbeat due in
     * {@code waitNs}: a NONE message {@code held} for lane 0 is looked at again every millisecond,
     * for the rare acknowledgement whose nudge misses the writer (lane 0 only tries this lane's
     * lock, never waits for it: see {@code Link.nudge}).
     */
    static long waitNs(long waitNs, boolean held) {
        return held ? Math.min(waitNs, BARRIER_POLL_NS) : waitNs;
    }
}
