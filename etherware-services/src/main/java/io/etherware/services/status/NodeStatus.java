package io.etherware.services.status;

import io.etherware.core.message.Contents;
import java.util.List;
import java.util.Objects;

/**
 * What a node reports about itself ({@link Status#snapshot}): its components, its dispatchers'
 * latency and deadline misses, its network peers with their clock offsets, and its counters, read
 * at one moment (each figure exact; not all read atomically together). Immutable; the reply to a
 * {@link StatusRequest}, wire name {@value Status#NODE_STATUS}.
 *
 * @param nodeId      the node
 * @param epochNs     when it was read, on the node's epoch clock (nanoseconds)
 * @param scheduler   the scheduler's description (its class and dispatchers)
 * @param components  every component, by profile
 * @param dispatchers every dispatcher of a real-time scheduler (none for another scheduler)
 * @param peers       every network peer known to the node (none without a network)
 * @param counters    the node's counters
 */
public record NodeStatus(String nodeId, long epochNs, String scheduler, List<ComponentEntry> components,
                         List<DispatcherEntry> dispatchers, List<PeerEntry> peers, Counters counters)
        implements Contents {

    /** Copies the lists; nothing may be null. */
    public NodeStatus {
        Objects.requireNonNull(nodeId, "nodeId");
        Objects.requireNonNull(scheduler, "scheduler");
        components = List.copyOf(components);
        dispatchers = List.copyOf(dispatchers);
        peers = List.copyOf(peers);
        Objects.requireNonNull(counters, "counters");
    }

    /**
     * One component.
     *
     * @param profile        its profile
     * @param state          its shell's state ({@code RUNNING}, {@code HELD}, ...)
     * @param logic          the class of its logic
     * @param handled        messages it handled without an exception
     * @param failed         messages whose handling threw
     * @param restarts       restarts by its supervision
     * @param deadlineMisses its jobs that completed after their deadline (real-time scheduler;
     *                       0 otherwise)
     * @param maxExecutionNs its longest job, in nanoseconds (real-time scheduler; 0 otherwise)
     */
    public record ComponentEntry(String profile, String state, String logic, long handled, long failed,
                                 long restarts, long deadlineMisses, long maxExecutionNs) {
    }

    /**
     * One dispatcher of a real-time scheduler: release-to-start latency of its jobs.
     *
     * @param id             its index (0 is the non-real-time one in Table II)
     * @param jobsRun        jobs it ran
     * @param deadlineMisses jobs that completed after their deadline
     * @param queuedJobs     jobs waiting in its queue (approximate)
     * @param p50Ns          median start latency
     * @param p99Ns          99th percentile start latency
     * @param maxNs          largest start latency
     */
    public record DispatcherEntry(int id, long jobsRun, long deadlineMisses, long queuedJobs, long p50Ns, long p99Ns,
                                  long maxNs) {
    }

    /**
     * One network peer.
     *
     * @param nodeId        its node id
     * @param connected     whether a connection to it is up
     * @param remote        its address, or empty if none is known
     * @param queued        messages waiting to be written to it
     * @param profiles      the profiles it announced
     * @param clockOffsetNs its clock minus this node's, as NetworkTime estimates it, or null before
     *                      the first estimate
     * @param roundTripNs   the round trip of the best recent time probe, or null before the first
     */
    public record PeerEntry(String nodeId, boolean connected, String remote, int queued, int profiles,
                            Long clockOffsetNs, Long roundTripNs) {
    }

    /**
     * The node's counters ({@link io.etherware.core.kernel.NodeStats}).
     *
     * @param handled         messages handled without an exception
     * @param failed          messages whose handling threw
     * @param restarts        restarts by components' supervision
     * @param undeliverable   messages that could not be delivered
     * @param requestTimeouts requests that got no reply in time
     * @param deadlineMisses  jobs that completed after their deadline, all dispatchers
     */
    public record Counters(long handled, long failed, long restarts, long undeliverable, long requestTimeouts,
                           long deadlineMisses) {
    }
}
