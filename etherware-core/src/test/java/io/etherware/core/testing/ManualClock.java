package io.etherware.core.testing;

import io.etherware.core.time.NodeClock;
import java.util.concurrent.atomic.AtomicLong;

/**
 * A clock the test sets; epoch time follows the monotonic time from a fixed origin. The same as
 * etherware-testkit's {@code io.etherware.testkit.ManualClock}, which this module's tests cannot use:
 * the test kit depends on this module.
 */
public final class ManualClock implements NodeClock {

    private static final long EPOCH_ORIGIN_NS = 1_700_000_000_000_000_000L;
    private final AtomicLong nowNs = new AtomicLong();

    public void set(long ns) {
        nowNs.set(ns);
    }

    public void advance(long ns) {
        nowNs.addAndGet(ns);
    }

    @Override
    public long nanoTime() {
        return nowNs.get();
    }

    @Override
    public long epochNanos() {
        return EPOCH_ORIGIN_NS + nowNs.get();
    }
}
