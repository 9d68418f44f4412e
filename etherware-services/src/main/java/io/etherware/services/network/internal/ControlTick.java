package io.etherware.services.network.internal;

import io.etherware.core.message.Profile;
import io.etherware.services.network.CloseReason;
import java.util.List;
import java.util.Queue;
import java.util.concurrent.ConcurrentMap;
import java.util.concurrent.TimeUnit;
import org.slf4j.Logger;
import org.slf4j.LoggerFactory;

/**
 * The messenger's periodic duties, one round every {@value Engine#TICK_MS} ms: the dialers'
 * redials; for each connected lane, closing it if the peer reads nothing, asking for owed
 * acknowledgements and (lane 0) time probes; for a peer down the grace period, giving up its
 * messages and routes; then reconciling the routes of the profiles the {@link Announcer} queued.
 *
 * <p>Thread-safety: {@link #run} runs on the control thread only (scheduled by {@link Engine});
 * the dialers, peers and profiles it walks are concurrent collections shared with the engine.
 */
final class ControlTick implements Runnable {

    private static final Logger log = LoggerFactory.getLogger("io.etherware.services.network.NetworkMessenger");
    private static final long BURST_SPACING_NS = TimeUnit.MILLISECONDS.toNanos(20);

    private final NetworkContext context;
    private final List<Dialer> dialers;
    private final ConcurrentMap<String, Peer> peers;
    private final Queue<Profile> toReconcile;
    private final RouteTable routes;
    private final StateSignal stateChanged;

    /**
     * @param dialers     the engine's dialers, one per configured peer address and lane
     * @param peers       the engine's peers by node id; a peer given up is removed
     * @param toReconcile profiles whose routes the announcer asks to reconcile
     */
    ControlTick(NetworkContext context, List<Dialer> dialers, ConcurrentMap<String, Peer> peers,
                Queue<Profile> toReconcile, RouteTable routes, StateSignal stateChanged) {
        this.context = context;
        this.dialers = dialers;
        this.peers = peers;
        this.toReconcile = toReconcile;
        this.routes = routes;
        this.stateChanged = stateChanged;
    }

    @Override
    public void run() {
        try {
            long nowNs = NetworkContext.nowNs();
            for (Dialer dialer : dialers) {
                dialer.maybeDial(nowNs);
            }
            for (Peer peer : peers.values()) {
                boolean up = false;
                for (Link link : peer.links()) {
                    up |= checkLink(link, nowNs);
                }
                if (!up) {
                    expireIfDown(peer, nowNs);
                } else {
                    for (Link link : peer.links()) {
                        reportLost(link.expireAlone(nowNs), peer, "its lane " + link.lane);
                    }
                }
            }
            Profile profile;
            while ((profile = toReconcile.poll()) != null) {
                routes.reconcile(profile);
            }
        } catch (RuntimeException e) {
            log.error("node {}: network control tick failed; continuing", context.nodeId(), e);
        }
    }

    /**
     * A connected lane's periodic duties: closes it if the peer reads nothing, asks for owed
     * acknowledgements, and (lane 0) time probes. Returns whether the lane is connected.
     */
    private boolean checkLink(Link link, long nowNs) {
        Connection active = link.active();
        if (active == null) {
            return false;
        }
        long stalledNs = link.unreadForNs(nowNs);
        if (stalledNs > context.config().heartbeatTimeoutNs()) {
            active.abort(CloseReason.NOT_READING, "node '" + link.nodeId + "' acknowledged nothing of what was"
                    + " written to it on lane " + link.lane + " for " + TimeUnit.NANOSECONDS.toMillis(stalledNs) + " ms");
            return true;
        }
        if (active.output().owesAck()) {
            active.requestAck();
        }
        if (link.lane == 0 && nowNs - active.nextProbeNs >= 0) {
            active.requestProbe();
            active.probesSent++;
            active.nextProbeNs = nowNs + (active.probesSent < context.config().timeProbeBurst() ? BURST_SPACING_NS
                    : context.config().timeProbeIntervalNs());
        }
        return true;
    }

    private void expireIfDown(Peer peer, long nowNs) {
        List<Outgoing> lost = peer.expireIfDown(nowNs);
        if (lost == null) {
            return;
        }
        routes.forget(peer);
        peers.remove(peer.nodeId, peer);
        reportLost(lost, peer, "unrouting its profiles");
        stateChanged.signal();
    }

    /** Logs and reports to their senders messages given up for a peer unreachable for the grace period. */
    private void reportLost(List<Outgoing> lost, Peer peer, String what) {
        if (lost == null) {
            return;
        }
        long graceMs = TimeUnit.NANOSECONDS.toMillis(context.config().peerDownGraceNs());
        log.warn("node {}: node '{}' has been unreachable for over {} ms ({}): reporting {} waiting messages as"
                + " undeliverable", context.nodeId(), peer.nodeId, graceMs, what, lost.size());
        for (Outgoing each : lost) {
            context.losses().lost(each.message(), "node '" + peer.nodeId + "' has been unreachable for over "
                    + graceMs + " ms");
        }
    }
}
