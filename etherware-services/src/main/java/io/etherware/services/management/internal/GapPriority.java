package io.etherware.services.management.internal;

import io.etherware.core.kernel.Kernel;
import io.etherware.rt.platform.CpuSet;
import io.etherware.rt.platform.Platform;
import io.etherware.rt.platform.ThreadPolicy;
import io.etherware.rt.scheduling.RealtimeScheduler;

/**
 * The OS policy of the thread that drives a migration from its source while the component is
 * held (the migration gap: hold, snapshot, install, relocate, hand-over), and back to the
 * thread's own policy afterwards. The service's worker is an ordinary thread, right for loading
 * and constructing code; but every step of the gap wakes it, and an ordinary thread woken on a
 * busy machine waits behind the JIT compiler, the collector and every other ordinary thread (on
 * the development box, wake-ups of 1 to 5 ms in the tail of each step). With the node's {@link
 * RealtimeScheduler}, the gap runs at the level of its highest real-time dispatcher, the one
 * Table II gives HIGH messages, the management requests' criticality: the priority the paper gives
 * an upgrade's management request. With any other scheduler the thread stays as it is.
 *
 * <p>The thread only waits for answers during the gap (and encodes the state into the install
 * step); it never spins. A refusal of the policy is warned once by the platform, and the gap runs
 * at ordinary priority as before.
 *
 * <p>Thread-safety: {@link #raise} and {@link Raised#close} on the one thread they change.
 */
final class GapPriority {

    private final ThreadPolicy policy;

    /** @param policy the policy of the gap; an ordinary one leaves threads as they are */
    GapPriority(ThreadPolicy policy) {
        this.policy = policy;
    }

    /** The gap's policy for {@code kernel}'s node: its highest real-time dispatcher's, or none. */
    static GapPriority of(Kernel kernel) {
        return new GapPriority(kernel.scheduler() instanceof RealtimeScheduler realtime
                ? realtime.config().threadSchedulingRule().above(0) : ThreadPolicy.NON_REALTIME);
    }

    /** The policy the gap asks for. */
    ThreadPolicy policy() {
        return policy;
    }

    /** Gives the calling thread the gap's policy until the returned handle is closed. */
    Raised raise() {
        if (!policy.isRealtime()) {
            return Raised.NONE;
        }
        Platform platform = Platform.current();
        ThreadPolicy before = platform.currentThreadPolicy();
        platform.configureCurrentThread(policy, CpuSet.inherit());
        return new Raised(before);
    }

    /** The calling thread's policy before {@link #raise}, put back by {@link #close}. */
    static final class Raised implements AutoCloseable {
        static final Raised NONE = new Raised(null);
        private final ThreadPolicy before;

        private Raised(ThreadPolicy before) {
            this.before = before;
        }

        @Override
        public void close() {
            if (before != null) {
                Platform.current().configureCurrentThreadWithoutWarning(before, CpuSet.inherit());
            }
        }
    }
}
