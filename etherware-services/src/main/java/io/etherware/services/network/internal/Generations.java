package io.etherware.services.network.internal;

import java.util.ArrayDeque;

/**
 * A lane's messages that are not yet settled, counted by generation: each message taken for the
 * lane belongs to the generation open when it was taken, and is settled when the peer acknowledges
 * it or the lane gives it up for good (evicted, refused, reported lost). A NONE message of lane 1
 * closes lane 0's open generation and waits until every message of it and of the earlier ones is
 * settled ({@link #settledUpTo}): exactly the messages queued for the peer before it, whatever
 * order lane 0's queue writes them in and whatever happens to lane 0's stream numbering meanwhile.
 *
 * <p>Locking: changed under its link's lock; {@link #settledUpTo} reads a volatile and takes no
 * lock, so lane 1 asks it without touching lane 0's lock.
 */
final class Generations {

    /** Generations with unsettled messages, oldest first: {generation, count}. */
    private final ArrayDeque<long[]> pending = new ArrayDeque<>();
    private long open;
    /** The oldest generation with an unsettled message, or the open one when none is unsettled. */
    private volatile long oldestUnsettled;

    /** A message is taken for the lane: returns its generation. */
    long take() {
        long[] newest = pending.peekLast();
        if (newest != null && newest[0] == open) {
            newest[1]++;
        } else {
            pending.addLast(new long[] {open, 1});
        }
        oldestUnsettled = pending.peekFirst()[0];
        return open;
    }

    /** Closes the open generation and returns it: what a NONE message of lane 1 waits for. */
    long close() {
        long closed = open++;
        if (pending.isEmpty()) {
            oldestUnsettled = open;
        }
        return closed;
    }

    /** The message of {@code generation} is settled. */
    void settle(long generation) {
        for (long[] each : pending) {
            if (each[0] == generation) {
                each[1]--;
                break;
            }
        }
        while (!pending.isEmpty() && pending.peekFirst()[1] <= 0) {
            pending.pollFirst();
        }
        oldestUnsettled = pending.isEmpty() ? open : pending.peekFirst()[0];
    }

    /** Whether every message of {@code generation} and earlier is settled. Lock-free. */
    boolean settledUpTo(long generation) {
        return oldestUnsettled > generation;
    }
}
