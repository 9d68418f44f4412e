package io.etherware.core.component;

import io.etherware.core.message.Profile;

/**
 * The kernel-side Façade around one component (paper Section III-B): its lifecycle, its counters,
 * and the logic reference that supervision restarts and an upgrade swaps. This view is read-only;
 * the kernel owns the mechanism.
 *
 * <p>The shell guarantees that its component handles one message at a time (design decision 3),
 * across all dispatchers. A message for a component that is busy waits with the shell, ordered by
 * the scheduler's urgency, and never blocks a dispatcher. So a message waits at most for the one
 * handling already in progress on its component, plus the more urgent messages that were already
 * waiting for it: that is the bound on priority inversion the kernel adds.
 *
 * <p>Thread-safety: every method may be called from any thread. Counters are read without
 * locking and may lag the component by one message.
 */
public interface Shell {

    /** Lifecycle of a component. */
    enum State {
        /** Added, not started yet; messages for it wait. */
        CREATED,
        /** {@link Component#onStart} is running. */
        STARTING,
        /** Handling messages. */
        RUNNING,
        /** {@link Component#onStop} is running. */
        STOPPING,
        /** Stopped normally (removed, or the node closed). */
        STOPPED,
        /** Refused to start, or stopped by its restart policy after a failure. */
        FAILED
    }

    /** {@return the profile the component was registered with} */
    Profile profile();

    /** {@return the lifecycle state now} */
    State state();

    /** {@return how many messages the component handled without an exception} */
    long handledCount();

    /** {@return how many messages the component's handling threw on} */
    long failedCount();

    /** {@return the restarts applied by the restart policy (not counting node-wide resets)} */
    long restartCount();

    /** {@return how long the last handling took, in nanoseconds of the node's monotonic clock} */
    long lastHandlingNs();

    /** {@return the class of the current logic; it changes when an upgrade swaps it} */
    Class<? extends Component> logicType();
}
