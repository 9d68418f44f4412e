package io.etherware.services.notifier;

import io.etherware.services.notifier.internal.Sleeper;
import io.etherware.testkit.ManualClock;
import java.util.concurrent.locks.LockSupport;
import java.util.function.LongUnaryOperator;

/**
 * Sleeps in virtual time: jumps the manual clock to each deadline (plus an injected stall) at
 * once, up to a horizon; past it, parks until unparked, so the Notifier idles when the test has
 * seen enough.
 */
final class VirtualSleeper implements Sleeper {

    private final ManualClock clock;
    private final long horizonNs;
    private final LongUnaryOperator stallNs;

    /**
     * @param horizonNs the last deadline to jump to
     * @param stallNs   how late the thread "wakes" for a deadline: deadline -&gt; extra ns
     */
    VirtualSleeper(ManualClock clock, long horizonNs, LongUnaryOperator stallNs) {
        this.clock = clock;
        this.horizonNs = horizonNs;
        this.stallNs = stallNs;
    }

    @Override
    public void sleepUntil(long deadlineNs) {
        if (deadlineNs > horizonNs) {
            LockSupport.park(this);
            return;
        }
        clock.set(Math.max(clock.nanoTime(), deadlineNs + stallNs.applyAsLong(deadlineNs)));
    }
}
