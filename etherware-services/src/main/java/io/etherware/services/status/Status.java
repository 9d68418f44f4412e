package io.etherware.services.status;

import io.etherware.core.component.Shell;
import io.etherware.core.kernel.EtherwareNode;
import io.etherware.core.kernel.Kernel;
import io.etherware.core.kernel.NodeStats;
import io.etherware.core.message.ContentsTypes;
import io.etherware.core.message.Criticality;
import io.etherware.core.message.Message;
import io.etherware.core.message.Profile;
import io.etherware.core.message.QoS;
import io.etherware.rt.scheduling.ComponentStats;
import io.etherware.rt.scheduling.DispatcherStats;
import io.etherware.rt.scheduling.RealtimeScheduler;
import io.etherware.rt.scheduling.SchedulerStats;
import io.etherware.services.network.NetworkMessenger;
import io.etherware.services.network.PeerStatus;
import java.time.Duration;
import java.util.ArrayList;
import java.util.Comparator;
import java.util.Map;
import java.util.Objects;
import java.util.concurrent.CompletableFuture;

/**
 * A node's status: read it here ({@link #snapshot}), or ask another node's {@link StatusService}
 * for its ({@link #request}). Stateless.
 */
public final class Status {

    /** The role of every node's status service: {@code etherware.status[node=<id>]}. */
    public static final String ROLE = "etherware.status";
    /** Wire name of {@link StatusRequest}. */
    public static final String STATUS_REQUEST = "etherware.statusRequest";
    /** Wire name of {@link NodeStatus}. */
    public static final String NODE_STATUS = "etherware.nodeStatus";
    /** Status requests travel at MIDDLE: above LOW background work, never in a HIGH loop's way. */
    public static final QoS REQUEST_QOS = QoS.of(Criticality.MIDDLE);

    private Status() {
    }

    /**
     * The profile of node {@code nodeId}'s status service.
     *
     * @param nodeId the node
     * @return {@code etherware.status[node=<nodeId>]}
     */
    public static Profile profileOf(String nodeId) {
        return Profile.of(ROLE, "node", nodeId);
    }

    /**
     * Registers {@link StatusRequest} and {@link NodeStatus} in {@code types}. Idempotent.
     *
     * @param types the registry
     */
    public static void registerContents(ContentsTypes types) {
        types.register(STATUS_REQUEST, StatusRequest.class);
        types.register(NODE_STATUS, NodeStatus.class);
    }

    /**
     * Reads {@code node}'s status now.
     *
     * @param node    the node
     * @param network its messenger, or null if it has none
     * @return the status
     */
    public static NodeStatus snapshot(EtherwareNode node, NetworkMessenger network) {
        Objects.requireNonNull(node, "node");
        SchedulerStats schedulerStats = node.scheduler() instanceof RealtimeScheduler realtime ? realtime.stats() : null;
        Map<String, ComponentStats> byComponent = schedulerStats != null ? schedulerStats.components() : Map.of();
        var components = new ArrayList<NodeStatus.ComponentEntry>();
        for (Shell shell : node.shells()) {
            ComponentStats stats = byComponent.get(shell.profile().toString());
            components.add(new NodeStatus.ComponentEntry(shell.profile().toString(), shell.state().name(),
                    shell.logicType().getName(), shell.handledCount(), shell.failedCount(), shell.restartCount(),
                    stats != null ? stats.deadlineMisses() : 0, stats != null ? stats.maxExecutionNs() : 0));
        }
        components.sort(Comparator.comparing(NodeStatus.ComponentEntry::profile));
        var dispatchers = new ArrayList<NodeStatus.DispatcherEntry>();
        if (schedulerStats != null) {
            for (DispatcherStats stats : schedulerStats.dispatchers()) {
                var latency = stats.startLatencyNs();
                dispatchers.add(new NodeStatus.DispatcherEntry(stats.dispatcherId(), stats.jobsRun(),
                        stats.deadlineMisses(), stats.queuedJobs(), latency.count() == 0 ? 0 : latency.percentileNs(50),
                        latency.count() == 0 ? 0 : latency.percentileNs(99), latency.maxNs()));
            }
        }
        var peers = new ArrayList<NodeStatus.PeerEntry>();
        if (network != null) {
            for (PeerStatus peer : network.peers()) {
                peers.add(new NodeStatus.PeerEntry(peer.nodeId(), peer.connected(), peer.remote().orElse(""),
                        peer.queued(), peer.profiles().size(),
                        peer.time().map(time -> time.offsetNs()).orElse(null),
                        peer.time().map(time -> time.roundTripNs()).orElse(null)));
            }
        }
        NodeStats stats = node.stats();
        var counters = new NodeStatus.Counters(stats.handled(), stats.failed(), stats.restarts(), stats.undeliverable(),
                stats.requestTimeouts(), schedulerStats != null ? schedulerStats.deadlineMisses() : 0);
        String scheduler = node.scheduler() instanceof RealtimeScheduler realtime
                ? "realtime " + realtime.config().threadSchedulingRule()
                : node.scheduler().getClass().getSimpleName() + " " + node.scheduler().name();
        return new NodeStatus(node.nodeId(), node.clock().epochNanos(), scheduler, components,
                dispatchers, peers, counters);
    }

    /**
     * Asks node {@code nodeId}'s status service for its status, from outside any component.
     *
     * @param kernel  the asking node; its node profile is the sender
     * @param nodeId  the node to ask (this one, or one a network route reaches)
     * @param timeout how long to wait for the answer, &gt; 0
     * @return the status; fails with {@link io.etherware.core.component.RequestFailedException}
     *         when no answer came, or {@link IllegalStateException} for an answer of another type
     */
    public static CompletableFuture<NodeStatus> request(Kernel kernel, String nodeId, Duration timeout) {
        Objects.requireNonNull(kernel, "kernel");
        registerContents(kernel.contentsTypes());
        var request = new Message(profileOf(nodeId), kernel.profile(), kernel.clock().epochNanos(), REQUEST_QOS,
                new StatusRequest(), kernel.newMessageId(), null);
        return kernel.request(request, timeout.toNanos()).thenApply(reply -> switch (reply.contents()) {
            case NodeStatus status -> status;
            default -> throw new IllegalStateException("the answer " + reply.messageId() + " to a status request"
                    + " carries " + reply.contents().getClass().getSimpleName() + ", not a node status");
        });
    }
}
