package io.etherware.rt.scheduling;

import io.etherware.core.time.NodeClock;
import java.util.concurrent.atomic.AtomicLong;

/** A clock that moves only when told: exact, deterministic timings in tests. */
final class ManualClock implements NodeClock {

    private final AtomicLong nowNs = new AtomicLong(1_000_000_000L);

    @Override
    public long nanoTime() {
        return nowNs.get();
    }

    @Override
    public long epochNanos() {
        return nowNs.get();
    }

    void advance(long ns) {
        nowNs.addAndGet(ns);
    }

    void set(long ns) {
        nowNs.set(ns);
    }
}
