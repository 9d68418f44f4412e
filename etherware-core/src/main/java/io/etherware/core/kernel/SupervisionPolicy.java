package io.etherware.core.kernel;

import java.time.Duration;
import java.util.Objects;

/**
 * What the kernel does when a component throws (the Management Tree of the Fraunhofer framework,
 * with Erlang-style restart intensity): restart it from its last snapshot, restart it fresh, or
 * stop it; at most {@code maxRestarts} restarts within {@code windowNs}, past which the failure
 * escalates to the node's {@link Escalation}.
 *
 * <p>Immutable; validated at construction.
 *
 * @param restart     how to restart
 * @param maxRestarts restarts allowed within the window before escalating; 0 escalates at the
 *                    first failure. Ignored for {@link Restart#STOP}.
 * @param windowNs    the sliding window of the intensity limit, in nanoseconds; &gt; 0
 */
public record SupervisionPolicy(Restart restart, int maxRestarts, long windowNs) {

    /** How a failed component comes back. */
    public enum Restart {
        /**
         * A new instance, restored from the last snapshot taken after a successfully handled
         * message (so the state is never the half-updated state of the failed handling). The
         * kernel calls {@code snapshot()} after every handled message.
         */
        FROM_SNAPSHOT,
        /** A new instance from the factory, without state. */
        FRESH,
        /** No restart: the component goes to {@code FAILED}; messages for it are undeliverable. */
        STOP
    }

    /** The largest intensity limit accepted (the kernel keeps one time stamp per allowed restart). */
    public static final int MAX_RESTARTS_LIMIT = 100_000;

    /** The default: restart from the last snapshot, at most 3 times in 5 seconds. */
    public static final SupervisionPolicy DEFAULT = fromSnapshot(3, Duration.ofSeconds(5));

    /**
     * Checks the components.
     *
     * @throws IllegalArgumentException naming the field if {@code maxRestarts} is outside
     *                                  [0, {@link #MAX_RESTARTS_LIMIT}] or {@code windowNs} is not
     *                                  positive
     */
    public SupervisionPolicy {
        Objects.requireNonNull(restart, "restart");
        if (maxRestarts < 0 || maxRestarts > MAX_RESTARTS_LIMIT) {
            throw new IllegalArgumentException("maxRestarts=" + maxRestarts + " must be in [0, " + MAX_RESTARTS_LIMIT + "]");
        }
        if (windowNs <= 0) {
            throw new IllegalArgumentException("windowNs=" + windowNs + " must be > 0 (e.g. 5 s = 5_000_000_000)");
        }
    }

    /**
     * Restart from the last snapshot, at most {@code maxRestarts} times within {@code window}.
     *
     * @param maxRestarts restarts allowed within the window, 0 to {@link #MAX_RESTARTS_LIMIT}
     * @param window      the sliding window of the limit; positive
     * @return the policy
     * @throws IllegalArgumentException if {@code maxRestarts} is out of range, or {@code window} is
     *                                  not positive or too long to count in nanoseconds
     */
    public static SupervisionPolicy fromSnapshot(int maxRestarts, Duration window) {
        return new SupervisionPolicy(Restart.FROM_SNAPSHOT, maxRestarts, toNs("window", window));
    }

    /**
     * Restart fresh, at most {@code maxRestarts} times within {@code window}.
     *
     * @param maxRestarts restarts allowed within the window, 0 to {@link #MAX_RESTARTS_LIMIT}
     * @param window      the sliding window of the limit; positive
     * @return the policy
     * @throws IllegalArgumentException if {@code maxRestarts} is out of range, or {@code window} is
     *                                  not positive or too long to count in nanoseconds
     */
    public static SupervisionPolicy fresh(int maxRestarts, Duration window) {
        return new SupervisionPolicy(Restart.FRESH, maxRestarts, toNs("window", window));
    }

    /** {@return a policy that never restarts: the first failure stops the component} */
    public static SupervisionPolicy stop() {
        return new SupervisionPolicy(Restart.STOP, 0, 1);
    }

    static long toNs(String field, Duration duration) {
        return io.etherware.core.time.Durations.toNs(field, duration);
    }
}
