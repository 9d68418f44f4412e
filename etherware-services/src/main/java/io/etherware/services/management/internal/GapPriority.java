package io.etherware.services.management.internal;

import io.etherware.core.kernel.Kernel;
import io.etherware.core.message.Empty;
import io.etherware.core.message.Message;
import io.etherware.core.message.MessageId;
import io.etherware.core.message.Profile;
import io.etherware.core.message.QoS;
import io.etherware.core.scheduler.Job;
import io.etherware.rt.platform.CpuSet;
import io.etherware.rt.platform.Platform;
import io.etherware.rt.platform.ThreadPolicy;
import io.etherware.rt.scheduling.RealtimeScheduler;
import io.etherware.rt.scheduling.RealtimeSchedulerConfig;

/**
 * The OS policy of the thread that drives a migration from its source while the component is
 * held (the migration gap: hold, snapshot, install, relocate, hand-over), and back to the
 * thread's own policy afterwards. The service's worker is an ordinary thread, right for loading
 * and constructing code; but every step of the gap wakes it, and an ordinary thread woken on a
 * busy machine waits behind the JIT compiler, the collector and every other ordinary thread (on
 * the development box, 1 to 5 ms in the tail of each step). With the node's {@link
 * RealtimeScheduler}, the gap runs at the policy of the dispatcher its placement rule gives the
 * migration request itself: the request's priority, as an upgrade's swap runs at it (paper
 * Section VI-C; HIGH, Table II's dispatcher 1, for {@code Management.REQUEST_QOS}); a request
 * without QoS, or any other scheduler, leaves the thread as it is.
 *
 * <p>What runs at that policy: the waits for the hold and for the target's answers, the encoding
 * of the state into the install step and of the held messages the relocation forwards, and the
 * component's own {@code snapshot()} when the component is idle at the hold (the kernel then runs
 * the boundary action on the calling thread), as an upgrade runs it on the request's dispatcher.
 * The thread never spins. A refusal of the policy is warned once by the platform, and the gap runs
 * at ordinary priority as before.
 *
 * <p>Thread-safety: {@link #raise} and {@link Raised#close} on the one thread they change.
 */
final class GapPriority {

    private static final MessageId PROBE_ID = new MessageId("management", 0);

    private final ThreadPolicy policy;

    /** @param policy the policy of the gap; an ordinary one leaves threads as they are */
    GapPriority(ThreadPolicy policy) {
        this.policy = policy;
    }

    /**
     * The gap's policy on {@code kernel}'s node for a request of {@code qos} to {@code service}:
     * that of the dispatcher the real-time scheduler's placement rule puts such a message on, or
     * none with another scheduler.
     */
    static GapPriority of(Kernel kernel, Profile service, QoS qos) {
        if (!(kernel.scheduler() instanceof RealtimeScheduler realtime)) {
            return new GapPriority(ThreadPolicy.NON_REALTIME);
        }
        RealtimeSchedulerConfig config = realtime.config();
        var probe = new Message(service, null, 0L, qos, Empty.INSTANCE, PROBE_ID, null);
        int dispatcher = config.placementRule().place(new Job(probe, service.toString(), service, 0, 0L), 0L)
                .dispatcherId();
        return new GapPriority(config.threadSchedulingRule().dispatcher(dispatcher).policy());
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
        var raised = new Raised(platform.currentThreadPolicy());
        try {
            platform.configureCurrentThread(policy, CpuSet.inherit());
        } catch (RuntimeException | Error e) {
            raised.close(); // the policy may be set already
            throw e;
        }
        return raised;
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
