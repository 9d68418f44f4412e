package io.etherware.services.network.internal;

import java.time.Duration;
import java.util.concurrent.TimeUnit;
import java.util.function.BooleanSupplier;

/**
 * The wait for the messenger's routes or connections to change: {@link Engine#awaitConnected} and
 * {@link Engine#awaitResolvable} wait here until their condition holds, and whatever changes the
 * routes or connections signals.
 *
 * <p>Thread-safety: any thread. {@link #await} blocks its caller (an application thread, never a
 * connection's or the control thread); {@link #signal} holds the monitor only to notify.
 */
final class StateSignal {

    private final Object changed = new Object();

    /**
     * Waits until {@code condition} holds, checking it after each signal and at least every
     * {@value Engine#TICK_MS} ms; false if it still does not after {@code timeout}.
     */
    boolean await(Duration timeout, BooleanSupplier condition) throws InterruptedException {
        long deadlineNs = NetworkContext.nowNs() + timeout.toNanos();
        synchronized (changed) {
            while (!condition.getAsBoolean()) {
                long leftNs = deadlineNs - NetworkContext.nowNs();
                if (leftNs <= 0) {
                    return false;
                }
                // Bounded wait: a change signalled just before we waited is seen on the next round.
                changed.wait(Math.max(1, Math.min(Engine.TICK_MS, TimeUnit.NANOSECONDS.toMillis(leftNs))));
            }
            return true;
        }
    }

    /** The routes or connections changed: wakes every waiter to check its condition again. */
    void signal() {
        synchronized (changed) {
            changed.notifyAll();
        }
    }
}
