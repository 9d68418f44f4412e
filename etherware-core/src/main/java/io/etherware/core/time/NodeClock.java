package io.etherware.core.time;

/**
 * The clock of one node: a monotonic clock for everything measured inside the node, and an epoch
 * clock for message time stamps (design decision 7).
 *
 * <p>Implementations must be thread-safe and cheap; the dispatchers read {@link #nanoTime()} once
 * per job. Tests inject a manual clock.
 */
public interface NodeClock {

    /** {@return monotonic nanoseconds from an arbitrary origin, comparable only in this node} */
    long nanoTime();

    /** {@return nanoseconds since the Unix epoch, as this node believes it to be} */
    long epochNanos();

    /**
     * {@return the JVM's clocks: {@link System#nanoTime()} and the system wall clock} The same
     * stateless instance on every call.
     */
    static NodeClock system() {
        return SystemClock.INSTANCE;
    }
}
