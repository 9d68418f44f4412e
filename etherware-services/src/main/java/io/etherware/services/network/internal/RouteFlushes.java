package io.etherware.services.network.internal;

import io.etherware.core.kernel.Kernel;
import io.etherware.core.kernel.OrderMarker;
import io.etherware.core.message.Criticality;
import io.etherware.core.message.Message;
import io.etherware.core.message.Profile;
import io.etherware.core.message.QoS;
import java.security.SecureRandom;
import java.util.ArrayList;
import java.util.List;
import java.util.concurrent.ConcurrentHashMap;
import java.util.concurrent.RejectedExecutionException;
import java.util.concurrent.ScheduledExecutorService;
import java.util.concurrent.TimeUnit;
import org.slf4j.Logger;
import org.slf4j.LoggerFactory;

/**
 * The markers of {@link SenderOrder}, node-wide: sends them ({@link OrderMarker}, which the kernel
 * that finds the profile's component hosted answers), releases a held lane on its marker's answer
 * or after {@link #FLUSH_WAIT_NS}, and sends again what a route held when it stops serving its
 * profile.
 *
 * <p>Trust: the kernel answers a marker to the node the connection vouches for, never to a
 * profile the marker names; an answer only releases this node's own held messages, and only for
 * a token this node made (random, 64 bits), so a peer can neither redirect answers nor release a
 * lane early without the token.
 *
 * <p>Thread-safety: every method may be called from any thread.
 */
final class RouteFlushes {

    private static final Logger log = LoggerFactory.getLogger("io.etherware.services.network.NetworkMessenger");

    /**
     * How long a held lane waits for its marker's answer: far above a migration's hand-over on a
     * live link (milliseconds), short enough that a dead old host delays the lane only briefly.
     */
    static final long FLUSH_WAIT_NS = TimeUnit.SECONDS.toNanos(1);
    /** How long the markers wait for sends that read the old owner to hand their message over. */
    static final long DRAIN_WAIT_NS = TimeUnit.MILLISECONDS.toNanos(100);

    private record Pending(SenderOrder order, int lane, Profile profile) {
    }

    private final Kernel kernel;
    private final ScheduledExecutorService control;
    private final Losses losses;
    private final Counters counters;
    private final int laneCount;
    private final SecureRandom random = new SecureRandom();
    private final ConcurrentHashMap<Long, Pending> pending = new ConcurrentHashMap<>();

    RouteFlushes(Kernel kernel, ScheduledExecutorService control, Losses losses, Counters counters, int laneCount) {
        this.kernel = kernel;
        this.control = control;
        this.losses = losses;
        this.counters = counters;
        this.laneCount = laneCount;
    }

    int laneCount() {
        return laneCount;
    }

    int laneOf(Message message) {
        return NetworkContext.laneOf(laneCount, message.qos().criticality());
    }

    /**
     * The criticality of a lane's marker: the least critical the lane carries, so every queue on
     * the way (most critical first, FIFO within a level) puts it behind each earlier message of the
     * lane; a NONE message also waits for lane 0's earlier messages (see {@link Peer#enqueue}).
     */
    Criticality markerCriticality(int lane) {
        for (Criticality criticality : Criticality.values()) { // least critical first
            if (NetworkContext.laneOf(laneCount, criticality) == lane) {
                return criticality;
            }
        }
        throw new IllegalArgumentException("lane " + lane + " carries no criticality");
    }

    /**
     * Sends a marker for {@code profile} on {@code lane} through {@code via}; returns its token, or
     * 0 if {@code via} takes no message now (the lane then has nothing to wait for).
     */
    long sendMarker(SenderOrder order, int lane, Profile profile, Peer via) {
        long token;
        do {
            token = random.nextLong();
        } while (token == 0 || pending.putIfAbsent(token, new Pending(order, lane, profile)) != null);
        Message marker = new Message(profile, kernel.profile(), kernel.clock().epochNanos(),
                QoS.of(markerCriticality(lane)), new OrderMarker(token), kernel.newMessageId(), null);
        try {
            via.enqueue(marker);
        } catch (RuntimeException e) {
            if (via.isRetired()) {
                pending.remove(token);
                log.debug("node {}: node '{}' is gone, so nothing of this node's for '{}' is on its way there;"
                        + " lane {} goes on at once", kernel.nodeId(), via.nodeId, profile, lane);
                return 0;
            }
            // Refused for now (its queue is full): what went before may still be there, so the
            // lane waits for the timeout rather than overtake it.
            log.debug("node {}: node '{}' refused the order marker for '{}' ({}); lane {} waits {} ms",
                    kernel.nodeId(), via.nodeId, profile, e.toString(), lane, TimeUnit.NANOSECONDS.toMillis(FLUSH_WAIT_NS));
        }
        counters.routeFlushes.increment();
        log.debug("node {}: '{}' moved: lane {} held behind order marker {} sent through node '{}'", kernel.nodeId(),
                profile, lane, token, via.nodeId);
        final long sent = token;
        try {
            control.schedule(() -> expire(sent), FLUSH_WAIT_NS, TimeUnit.NANOSECONDS);
        } catch (RejectedExecutionException e) {
            // The messenger is closing: what is held is reported lost with everything else.
        }
        return token;
    }

    private void expire(long token) {
        Pending waited = pending.remove(token);
        if (waited != null && waited.order().release(waited.lane(), token)) {
            counters.routeFlushTimeouts.increment();
            log.warn("node {}: no node answered the order marker for '{}' (lane {}) within {} ms: its later messages"
                    + " go on to its new host; any this node sent it through its old host before may come after them"
                    + " or not at all", kernel.nodeId(), waited.profile(), waited.lane(),
                    TimeUnit.NANOSECONDS.toMillis(FLUSH_WAIT_NS));
        }
    }

    /** A marker's answer came (the connection's reader): releases the lane it is for, if it is one of ours. */
    void answered(long token) {
        Pending waited = pending.remove(token);
        if (waited != null) {
            waited.order().release(waited.lane(), token);
            log.debug("node {}: the order marker for '{}' was answered: lane {} goes on", kernel.nodeId(),
                    waited.profile(), waited.lane());
        }
    }

    /**
     * The sends that read a route's old owner did not all finish within {@link #DRAIN_WAIT_NS}: one
     * may land behind the marker (a thread stalled that long).
     */
    void drainTimedOut(Profile profile) {
        log.warn("node {}: a send to '{}' through its old host did not finish within {} ms; its order marker goes"
                + " now, and that message may be handled after later ones", kernel.nodeId(), profile,
                TimeUnit.NANOSECONDS.toMillis(DRAIN_WAIT_NS));
    }

    /**
     * Hands released messages, in order, to the route's owner now; returns the reports of any it
     * could not take, for the caller to run off its monitor (a report is a send to the kernel).
     */
    List<Runnable> deliverReleased(RouteTable.ProfileRoute route, List<Message> messages) {
        var reports = new ArrayList<Runnable>();
        if (!messages.isEmpty() && log.isDebugEnabled()) {
            log.debug("node {}: releasing {} held messages to '{}' ({} .. {}) to node '{}'", kernel.nodeId(),
                    messages.size(), route.profile, messages.getFirst().messageId(), messages.getLast().messageId(),
                    route.owner == null ? "-" : route.owner.nodeId);
        }
        for (Message message : messages) {
            Peer to = route.owner;
            try {
                if (to == null) {
                    throw new IllegalStateException("no connected node announces '" + route.profile + "' now");
                }
                to.enqueue(message);
            } catch (RuntimeException e) {
                String reason = "the route to '" + route.profile + "' refused it: " + e.getMessage();
                reports.add(() -> losses.lost(message, reason));
            }
        }
        return reports;
    }

    /**
     * Messages held for a route that no longer serves their profile (no node announces it, or a
     * component here took it over): sent again through the kernel, which finds where the profile
     * lives now, or reported undeliverable to their senders.
     */
    void resend(RouteTable.ProfileRoute route, List<Message> messages) {
        for (Message message : messages) {
            try {
                kernel.send(message);
            } catch (RuntimeException e) {
                losses.lost(message, "no node hosts '" + route.profile + "' any more: " + e.getMessage());
            }
        }
    }
}
