package io.etherware.testkit;

import java.util.concurrent.TimeUnit;
import java.util.function.BooleanSupplier;
import java.util.function.Supplier;

/**
 * Waits for a condition with a generous deadline: the box is shared with other builds, so a test
 * waits for an outcome, never for a duration. Called from the test's thread; polls every
 * millisecond.
 */
public final class Await {

    /** The deadline of {@link #until(String, BooleanSupplier)}. */
    public static final long DEADLINE_MS = 30_000;

    private Await() {
    }

    /** Returns once {@code condition} holds; fails after {@link #DEADLINE_MS} naming {@code what}. */
    public static void until(String what, BooleanSupplier condition) {
        until(what, DEADLINE_MS, condition);
    }

    /** Returns once {@code condition} holds; fails after {@code deadlineMs} naming {@code what}. */
    public static void until(String what, long deadlineMs, BooleanSupplier condition) {
        until(() -> what, deadlineMs, condition);
    }

    /**
     * Returns once {@code condition} holds; fails after {@code deadlineMs} with {@code what}, read
     * then, so that it can tell the state the wait ended in.
     */
    public static void until(Supplier<String> what, long deadlineMs, BooleanSupplier condition) {
        long deadlineNs = System.nanoTime() + TimeUnit.MILLISECONDS.toNanos(deadlineMs);
        while (!condition.getAsBoolean()) {
            if (System.nanoTime() - deadlineNs > 0) {
                throw new AssertionError("timed out after " + deadlineMs + " ms waiting for: " + what.get());
            }
            try {
                Thread.sleep(1);
            } catch (InterruptedException e) {
                Thread.currentThread().interrupt();
                throw new AssertionError("interrupted waiting for: " + what.get(), e);
            }
        }
    }
}
