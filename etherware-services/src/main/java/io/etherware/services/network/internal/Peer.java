package io.etherware.services.network.internal;

import io.etherware.core.message.Criticality;
import io.etherware.core.message.Message;
import java.util.ArrayList;
import java.util.List;

/**
 * Everything this node keeps about one other node: one {@link Link} per lane (its own connection,
 * streams and queue), the node's incarnation, and the version of its announcements applied here.
 * A message goes to the link of its criticality's lane.
 *
 * <p>Thread-safety: {@link #enqueue} from any thread without this object's monitor; activation,
 * expiry and announcements are serialized on it. Lock order: this, then a link's inbound stream and
 * lock (activation), or this, then the route table, the registry and the announcer, which takes a
 * link's lock (an announcement); nothing takes this monitor holding any of them.
 */
final class Peer {

    final String nodeId;
    private final NetworkContext context;
    private final Link[] links;
    // Guarded by this.
    private long incarnation;
    private long announceVersion = -1;
    private boolean retired;
    /**
     * When the last active connection of the node's incarnation {@link #silentIncarnation} ended
     * without a goodbye ({@link Connection#endedWithoutGoodbye}); -1 if it said goodbye, or that
     * incarnation connected again. A later incarnation's connection leaves it: the process that
     * left is gone for good. Both guarded by this.
     */
    private long silentSinceNs = -1;
    private long silentIncarnation;

    Peer(String nodeId, NetworkContext context) {
        this.nodeId = nodeId;
        this.context = context;
        this.links = new Link[context.lanes().size()];
        for (int lane = 0; lane < links.length; lane++) {
            links[lane] = new Link(nodeId, lane, context, lane == 0 ? null : links[0]);
        }
        if (links.length > 1) {
            links[0].follower = links[1];
        }
    }

    /**
     * Takes a message for this node, on its lane; see {@link Link#enqueue}. A NONE message goes
     * after every message queued for the node before it, on either lane, as on one connection: the
     * lowest criticality is the one that waits behind everything (the migration protocol counts on
     * it: see {@code ManagementService}). On lane 1 it therefore waits until every message lane 0
     * took before it is settled: acknowledged by the peer, or given up for good (see {@link
     * Generations}).
     */
    void enqueue(Message message) {
        int lane = context.laneOf(message.qos().criticality());
        long after = lane == 1 && message.qos().criticality() == Criticality.NONE ? links[0].closeGeneration() : -1;
        links[lane].enqueue(message, after);
    }

    Link link(int lane) {
        return links[lane];
    }

    List<Link> links() {
        return List.of(links);
    }

    /** Whether the messenger forgot this peer (gone for good): its queues take nothing more. */
    synchronized boolean isRetired() {
        return retired;
    }

    /** Every lane has its connection. */
    boolean isConnected() {
        for (Link link : links) {
            if (!link.isConnected()) {
                return false;
            }
        }
        return true;
    }

    /** An active connection of this node closed at {@code nowNs}; {@code withoutGoodbye}: see {@link #silentSinceNs}. */
    synchronized void connectionEnded(long nowNs, boolean withoutGoodbye) {
        if (withoutGoodbye) {
            silentSinceNs = nowNs;
            silentIncarnation = incarnation;
        } else if (silentIncarnation == incarnation) {
            silentSinceNs = -1;
        }
    }

    /**
     * When the node's process left without a goodbye, if it did: its last connection ended so and
     * no lane of the same incarnation has connected since (one of a later incarnation may have:
     * it restarted). -1 otherwise.
     */
    long goneSinceNs() {
        long since;
        long ofIncarnation;
        synchronized (this) {
            since = silentSinceNs;
            ofIncarnation = silentIncarnation;
            if (since < 0 || ofIncarnation != incarnation) {
                return since;
            }
        }
        for (Link link : links) {
            if (link.isConnected()) {
                return -1;
            }
        }
        return since;
    }

    /** The connection of lane 0, the one that carries the time exchange, or null. */
    Connection primary() {
        return links[0].active();
    }

    /**
     * Makes {@code candidate} its lane's connection (see {@link Link#activate}), unless this peer
     * expired meanwhile. {@code restarted} in the outcome: the node came back with a new incarnation.
     */
    synchronized Activation activate(Connection candidate, Frame.Hello hello, Frame.Resume theirs,
                                     java.util.function.Supplier<byte[]> announceBody) {
        if (retired) {
            return new Activation(new LaneActivation(false, candidate, List.of(), null), false);
        }
        LaneActivation activation = links[candidate.lane()].activate(candidate, theirs, announceBody);
        boolean restarted = false;
        if (activation.accepted()) {
            if (silentIncarnation == hello.incarnation()) {
                silentSinceNs = -1; // the same process came back: it had not left
            }
            restarted = incarnation != 0 && incarnation != hello.incarnation();
            if (incarnation != hello.incarnation()) {
                incarnation = hello.incarnation();
                announceVersion = -1; // a restarted node numbers its announcements from 0 again
            }
        }
        return new Activation(activation, restarted);
    }

    /** The outcome of {@link #activate}. */
    record Activation(LaneActivation link, boolean restarted) {
    }

    /**
     * Whether an ANNOUNCE of {@code version}, from a connection of the node's current incarnation,
     * is newer than the last one applied (each lane carries every announcement, ahead of its own
     * messages; the first copy to arrive is applied, so the routes a message needs are in place
     * whichever lane brings it). Runs {@code apply} if so.
     */
    synchronized void onAnnounce(long fromIncarnation, long version, Runnable apply) {
        // One from a connection of the node's previous life (still being read) is stale.
        if (!retired && fromIncarnation == incarnation && version > announceVersion) {
            announceVersion = version;
            apply.run();
        }
    }

    /**
     * If no lane has been connected for the grace period: retire the peer (the messenger forgets it;
     * a later connection gets a new one) and return what waited for it, to report to the senders.
     * Null if it is not newly expired.
     */
    synchronized List<Outgoing> expireIfDown(long nowNs) {
        if (retired) {
            return null;
        }
        for (Link link : links) {
            if (link.isConnected() || nowNs - link.downSinceNs() < context.config().peerDownGraceNs()) {
                return null;
            }
        }
        retired = true;
        var lost = new ArrayList<Outgoing>();
        for (Link link : links) {
            List<Outgoing> waited = link.expire();
            if (waited != null) {
                lost.addAll(waited);
            }
        }
        return lost;
    }

    /** The messenger closes: every lane refuses new messages; returns what waited. */
    List<Outgoing> close() {
        var lost = new ArrayList<Outgoing>();
        for (Link link : links) {
            lost.addAll(link.close());
        }
        return lost;
    }

    /** Waiting messages, and written ones not yet acknowledged, over all lanes. */
    int[] backlog() {
        int[] sum = new int[2];
        for (Link link : links) {
            int[] each = link.backlog();
            sum[0] += each[0];
            sum[1] += each[1];
        }
        return sum;
    }
}
