package io.etherware.testkit;

import io.etherware.core.time.NodeClock;
import java.util.concurrent.atomic.AtomicLong;

/**
 * A {@link NodeClock} that moves only when the test moves it: exact, deterministic timings. Epoch
 * time follows the monotonic time from a fixed origin. Thread-safe: a test may move it while a
 * node's threads read it.
 */
public final class ManualClock implements NodeClock {

    /** {@link #epochNanos()} at monotonic time 0: 2023-11-14T22:13:20Z. */
    public static final long EPOCH_ORIGIN_NS = 1_700_000_000_000_000_000L;

    private final AtomicLong nowNs;

    /** A clock at monotonic time 0. */
    public ManualClock() {
        this(0);
    }

    /** A clock at monotonic time {@code startNs}. */
    public ManualClock(long startNs) {
        nowNs = new AtomicLong(startNs);
    }

    @Override
    public long nanoTime() {
        return nowNs.get();
    }

    @Override
    public long epochNanos() {
        return EPOCH_ORIGIN_NS + nowNs.get();
    }

    /** Sets the monotonic time to {@code ns}. */
    public void set(long ns) {
        nowNs.set(ns);
    }

    /** Moves the monotonic time on by {@code ns}. */
    public void advance(long ns) {
        nowNs.addAndGet(ns);
    }
}
