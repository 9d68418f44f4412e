package io.etherware.services.notifier;

import io.etherware.core.time.NodeClock;
import java.util.concurrent.atomic.AtomicLong;

/** A clock that moves only when told: exact, deterministic release times in tests. */
final class ManualClock implements NodeClock {

    private final AtomicLong nowNs;

    ManualClock(long startNs) {
        nowNs = new AtomicLong(startNs);
    }

    @Override
    public long nanoTime() {
        return nowNs.get();
    }

    @Override
    public long epochNanos() {
        return 1_700_000_000_000_000_000L + nowNs.get();
    }

    void set(long ns) {
        nowNs.set(ns);
    }

    void advance(long ns) {
        nowNs.addAndGet(ns);
    }
}
