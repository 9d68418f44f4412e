package example.counter;

import java.util.concurrent.atomic.AtomicLong;

/**
 * Harness support: the switch and the counters shared by the {@link ChainCounter} versions, on
 * the class path so that versions loaded from jars share them too.
 */
public final class Chain {

    /** While true, each chain counter sends itself the next sequence number. */
    public static volatile boolean running;
    /** Set by the counter that saw {@link #running} false and sent nothing: the chain has ended. */
    public static volatile boolean ended = true;
    /** The last sequence number handled, by whichever version. */
    public static volatile long lastSequence = -1;
    /** Sequence numbers that did not follow the previous one (lost, duplicated or reordered). */
    public static final AtomicLong breaks = new AtomicLong();
    /** The first breaks, as {@code expected->got}. */
    public static final java.util.List<String> firstBreaks = new java.util.concurrent.CopyOnWriteArrayList<>();

    /** Counts a sequence number that does not follow {@code last}. */
    public static void broken(long last, long got) {
        if (breaks.incrementAndGet() <= 10) {
            firstBreaks.add((last + 1) + "->" + got);
        }
    }

    private Chain() {
    }
}
