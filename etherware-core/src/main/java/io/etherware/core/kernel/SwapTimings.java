package io.etherware.core.kernel;

/**
 * When a timed swap ({@link ComponentHost#swapAsync(io.etherware.core.message.Profile,
 * java.util.function.Supplier, java.util.function.LongConsumer)}) paused a component, on the node's monotonic clock
 * ({@link io.etherware.core.time.NodeClock#nanoTime()}). A time the kernel does not know is
 * {@link #UNKNOWN_NS}.
 *
 * <p>Immutable; safe to share between threads.
 *
 * @param lastOldHandlingEndNs when the old logic finished its last message, or {@link #UNKNOWN_NS}
 *                             if it handled none
 * @param swapStartNs          when the swap began at the message boundary (before the snapshot)
 * @param swapEndNs            when the new logic was in place and the old one stopped; messages
 *                             are let in again from here
 * @param stateSchemaVersion   {@link io.etherware.core.component.ComponentState#schemaVersion()} of
 *                             the state handed over, or -1 if the old logic had no state
 */
public record SwapTimings(long lastOldHandlingEndNs, long swapStartNs, long swapEndNs, int stateSchemaVersion) {

    /** A time the kernel does not know (not -1: a monotonic clock may read negative). */
    public static final long UNKNOWN_NS = Long.MIN_VALUE;

    /**
     * {@return how long the component was paused at its boundary, in nanoseconds
     * ({@code swapEndNs - swapStartNs}), or {@link #UNKNOWN_NS} if either end is unknown}
     */
    public long pauseNs() {
        return swapStartNs == UNKNOWN_NS || swapEndNs == UNKNOWN_NS ? UNKNOWN_NS : swapEndNs - swapStartNs;
    }
}
