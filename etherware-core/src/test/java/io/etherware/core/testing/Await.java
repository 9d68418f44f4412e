package io.etherware.core.testing;

import java.util.function.BooleanSupplier;

/**
 * Waits for a condition with a generous deadline: the box is shared with other builds. The same as
 * etherware-testkit's {@code io.etherware.testkit.Await}, which this module's tests cannot use: the
 * test kit depends on this module.
 */
public final class Await {

    public static final long DEADLINE_MS = 30_000;

    private Await() {
    }

    public static void until(String what, BooleanSupplier condition) {
        long deadline = System.nanoTime() + DEADLINE_MS * 1_000_000;
        while (!condition.getAsBoolean()) {
            if (System.nanoTime() > deadline) {
                throw new AssertionError("timed out after " + DEADLINE_MS + " ms waiting for: " + what);
            }
            try {
                Thread.sleep(1);
            } catch (InterruptedException e) {
                Thread.currentThread().interrupt();
                throw new AssertionError("interrupted waiting for: " + what, e);
            }
        }
    }
}
