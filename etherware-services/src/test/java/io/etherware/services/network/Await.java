package io.etherware.services.network;

import java.util.function.BooleanSupplier;

/** Waits for a condition with a generous deadline: the box is shared with other builds. */
final class Await {

    static final long DEADLINE_MS = 30_000;

    private Await() {
    }

    static void until(String what, BooleanSupplier condition) {
        until(what, DEADLINE_MS, condition);
    }

    static void until(String what, long deadlineMs, BooleanSupplier condition) {
        long deadline = System.nanoTime() + deadlineMs * 1_000_000;
        while (!condition.getAsBoolean()) {
            if (System.nanoTime() > deadline) {
                throw new AssertionError("timed out after " + deadlineMs + " ms waiting for: " + what);
            }
            try {
                Thread.sleep(2);
            } catch (InterruptedException e) {
                Thread.currentThread().interrupt();
                throw new AssertionError("interrupted waiting for: " + what, e);
            }
        }
    }
}
