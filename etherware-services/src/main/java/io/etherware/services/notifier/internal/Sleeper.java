package io.etherware.services.notifier.internal;

/**
 * How the Notifier thread waits for its next release: a seam so tests can run the Notifier on a
 * manual clock, deterministically.
 *
 * <p>Called only on the Notifier thread. {@link java.util.concurrent.locks.LockSupport#unpark}
 * of that thread must end the wait early (a subscription was added or the Notifier closes).
 */
@FunctionalInterface
public interface Sleeper {

    /**
     * Returns at or soon after {@code deadlineNs} on the Notifier's clock, or earlier when
     * unparked or spuriously; the caller re-reads the clock and loops. {@link Long#MAX_VALUE}
     * means "until unparked".
     */
    void sleepUntil(long deadlineNs);
}
