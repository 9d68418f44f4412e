package io.etherware.services.network.internal;

import io.etherware.core.kernel.Endpoint;
import io.etherware.core.kernel.ProfileRegistry;
import io.etherware.core.kernel.ProfileResolutionException;
import io.etherware.core.kernel.RemoteRoute;
import io.etherware.core.message.Message;
import io.etherware.core.message.Profile;
import io.etherware.services.network.AnnouncePolicy;
import java.util.HashMap;
import java.util.HashSet;
import java.util.LinkedHashMap;
import java.util.LinkedHashSet;
import java.util.List;
import java.util.Map;
import java.util.Set;
import java.util.concurrent.RejectedExecutionException;
import java.util.concurrent.ScheduledExecutorService;
import java.util.concurrent.TimeUnit;
import java.util.concurrent.atomic.LongAdder;
import org.slf4j.Logger;
import org.slf4j.LoggerFactory;

/**
 * The profiles other nodes announced, and the {@link RemoteRoute}s registered for them in this
 * node's registry so that {@code send} to such a profile reaches the node hosting it.
 *
 * <p>What a peer may announce: its own node profile ({@code etherware.node[id=<its id>]}) and no
 * other node's, and the application profiles the {@link AnnouncePolicy} allows it; anything else
 * is refused, counted and logged. Conflicts: a local component wins over any announcement (the
 * registry refuses the route, and a component added later displaces it); among nodes announcing
 * the same profile, the first to announce it keeps it until it withdraws it (or is gone), and a
 * later claim waits in line, logged, never settled by node-id order: a newcomer cannot draw
 * traffic away from the node that serves it. A migration is such a hand-over: the source keeps
 * the route (and relays) until it withdraws the profile, then the target has it; this node's
 * messages to the profile keep their order across it ({@link SenderOrder}). A profile withdrawn by
 * its last host stays registered, its messages held, for {@link RouteFlushes#FLUSH_WAIT_NS}: the
 * target's announcement comes on another connection than the source's withdrawal and may come
 * second. A peer that is gone for good takes its profiles with it at once.
 *
 * <p>Thread-safety: changes are serialized on this object. Lock order: this, then the registry
 * (whose listener must therefore never call back in here; the messenger queues such work).
 */
final class RouteTable {

    private static final Logger log = LoggerFactory.getLogger(RouteTable.class);

    private static final String NODE_ROLE = "etherware.node";

    private final ProfileRegistry registry;
    private final AnnouncePolicy policy;
    private final LongAdder refused;
    private final RouteFlushes flushes;
    /** Runs the markers of a change of owner off this table's lock, and the end of a departed profile's wait. */
    private final ScheduledExecutorService control;
    private final Map<Profile, ProfileRoute> routes = new HashMap<>();
    private final Map<String, Set<Profile>> byPeer = new HashMap<>();
    /** A route a migration registered, to be replaced by the announced route once it leads there. */
    private record Provisional(RemoteRoute route, String nodeId) {
    }

    /** The routes migrations registered, by profile, until the announced route takes over. */
    private final Map<Profile, Provisional> provisional = new HashMap<>();
    private long refusalsLogged;
    /** Whether the hosts being removed are gone for good (no wait for another to announce). */
    private boolean forgetting;
    /** Whether the messenger closes: a profile no node announces is unrouted at once. */
    private boolean closing;

    /**
     * @param refused counts the announced profiles refused
     * @param flushes keeps this node's order to a profile whose host changes ({@link SenderOrder})
     * @param control where the markers of a change of host are sent from
     */
    RouteTable(ProfileRegistry registry, AnnouncePolicy policy, LongAdder refused, RouteFlushes flushes,
               ScheduledExecutorService control) {
        this.registry = registry;
        this.policy = policy;
        this.refused = refused;
        this.flushes = flushes;
        this.control = control;
    }

    /**
     * The route to one remote profile: it follows whichever node currently hosts it, keeping each
     * sender's order across a change of host ({@link SenderOrder}).
     */
    static final class ProfileRoute implements RemoteRoute {
        final Profile profile;
        final SenderOrder order;
        /** Nodes announcing the profile, in the order they claimed it; guarded by the table. */
        final LinkedHashMap<String, Peer> hosts = new LinkedHashMap<>();
        volatile Peer owner;
        /** The ids of {@link #hosts}, for readers outside the table's lock. */
        volatile Set<String> hostIds = Set.of();
        /** Whether the registry holds this route; guarded by the table. */
        boolean registered;
        boolean shadowLogged;

        ProfileRoute(Profile profile, RouteFlushes flushes) {
            this.profile = profile;
            this.order = new SenderOrder(this, flushes);
        }

        @Override
        public void deliver(Message message) {
            order.deliver(message);
        }

        @Override
        public boolean isServedBy(String nodeId) {
            return hostIds.contains(nodeId);
        }

        @Override
        public String toString() {
            Peer to = owner;
            return "network route to '" + profile + "' on node '" + (to == null ? "?" : to.nodeId) + "'";
        }
    }

    /** {@code peer} hosts exactly {@code profiles} now (an ANNOUNCE replaces the previous one). */
    synchronized void announce(Peer peer, List<Profile> profiles) {
        Set<Profile> now = new LinkedHashSet<>();
        for (Profile profile : profiles) {
            String refusal = refusal(peer.nodeId, profile);
            if (refusal == null) {
                now.add(profile);
            } else {
                refused.increment();
                if (refusalsLogged++ < 100 || refusalsLogged % 10_000 == 0) {
                    log.warn("node '{}' announced '{}': refused, {} ({} refusals so far)", peer.nodeId, profile,
                            refusal, refusalsLogged);
                }
            }
        }
        Set<Profile> before = byPeer.getOrDefault(peer.nodeId, Set.of());
        for (Profile profile : before) {
            if (!now.contains(profile)) {
                ProfileRoute route = routes.get(profile);
                route.hosts.remove(peer.nodeId);
                sync(route);
            }
        }
        for (Profile profile : now) {
            if (!before.contains(profile)) {
                ProfileRoute route = routes.computeIfAbsent(profile, p -> new ProfileRoute(p, flushes));
                if (!route.hosts.isEmpty()) {
                    log.info("profile '{}' announced by node '{}' stays routed to node '{}', which announced it first;"
                            + " the claim waits until that node withdraws it", profile, peer.nodeId,
                            route.hosts.firstEntry().getKey());
                }
                route.hosts.put(peer.nodeId, peer);
                sync(route);
            }
        }
        if (now.isEmpty()) {
            byPeer.remove(peer.nodeId);
        } else {
            byPeer.put(peer.nodeId, now);
        }
    }

    /** Why {@code nodeId} may not announce {@code profile}, or null if it may. */
    private String refusal(String nodeId, Profile profile) {
        if (profile.role().equals(NODE_ROLE)) {
            return profile.equals(Profile.of(NODE_ROLE, "id", nodeId)) ? null
                    : "a node may announce only its own node profile, " + Profile.of(NODE_ROLE, "id", nodeId);
        }
        return policy.allows(nodeId, profile) ? null : "this node's announce policy does not allow it from that node";
    }

    /** The peer is gone for good (grace expired, or the messenger closes): unroute its profiles. */
    synchronized void forget(Peer peer) {
        forgetting = true;
        try {
            announce(peer, List.of());
        } finally {
            forgetting = false;
        }
        provisional.values().removeIf(left -> left.nodeId().equals(peer.nodeId));
    }

    /** The registry changed for {@code profile} under our feet (a local component came or went). */
    synchronized void reconcile(Profile profile) {
        ProfileRoute route = routes.get(profile);
        if (route != null) {
            route.registered = isRegistered(route);
            sync(route);
        }
    }

    /**
     * {@code profile} is registered to {@code route}, which a migration away from this node left
     * (it leads to node {@code nodeId}, the target): replace it with the route that follows the
     * nodes announcing the profile, as soon as that route leads to the same node (now, or when
     * the target's announcement comes). In one step, so no send finds the profile unregistered;
     * both routes then queue for the target on the same streams, so no message overtakes another
     * of its sender. Forgotten if the target is forgotten first.
     */
    synchronized void adopt(Profile profile, RemoteRoute route, String nodeId) {
        provisional.put(profile, new Provisional(route, nodeId));
        ProfileRoute announced = routes.get(profile);
        if (announced != null) {
            sync(announced);
        }
    }

    /** The profiles routed to {@code nodeId}. */
    synchronized Set<Profile> hostedBy(String nodeId) {
        Set<Profile> announced = byPeer.getOrDefault(nodeId, Set.of());
        var routed = new HashSet<Profile>();
        for (Profile profile : announced) {
            ProfileRoute route = routes.get(profile);
            if (route != null && route.registered && route.owner != null && route.owner.nodeId.equals(nodeId)) {
                routed.add(profile);
            }
        }
        return routed;
    }

    private void sync(ProfileRoute route) {
        sync(route, false);
    }

    /** @param unrouteNow a profile no node announces is unrouted at once, not held for its next host */
    private void sync(ProfileRoute route, boolean unrouteNow) {
        route.hostIds = Set.copyOf(route.hosts.keySet());
        if (route.hosts.isEmpty()) {
            Peer last = route.owner;
            boolean stillOurs = !unrouteNow && !forgetting && !closing && route.registered && isRegistered(route);
            if (stillOurs && route.order.isDeparted()) {
                return; // waiting for the next host already (expireDeparted ends the wait)
            }
            if (last != null && stillOurs) {
                // Withdrawn by its last host: if the profile moved, its new host's announcement
                // is on its way on another connection. Hold its messages meanwhile (SenderOrder).
                long departure = route.order.departed(last);
                schedule(() -> expireDeparted(route, departure));
                return;
            }
            List<Message> held = route.order.abandon();
            route.owner = null;
            if (route.registered && isRegistered(route)) {
                try {
                    registry.unregisterRemote(route.profile);
                } catch (IllegalArgumentException e) {
                    // A local component displaced it just now; nothing of ours to remove.
                }
            }
            route.registered = false;
            routes.remove(route.profile);
            if (!held.isEmpty()) {
                try {
                    control.execute(() -> flushes.resend(route, held));
                } catch (RejectedExecutionException e) {
                    flushes.resend(route, held); // the messenger is closing: now
                }
            }
            return;
        }
        Peer first = route.hosts.firstEntry().getValue();
        Peer before = route.owner;
        if (before == null && !route.order.isDeparted()) {
            route.owner = first;
        } else if (before != first) {
            Runnable markers = route.order.ownerChanged(before, first);
            if (markers != null) {
                try {
                    control.execute(markers);
                } catch (RejectedExecutionException e) {
                    // The messenger is closing: forgetting its peers reports what is held.
                }
            }
        }

        Provisional left = route.registered ? null : provisional.get(route.profile);
        if (left != null && first.nodeId.equals(left.nodeId())) {
            provisional.remove(route.profile);
            if (registry.replaceRemote(route.profile, left.route(), route)) {
                route.registered = true;
                route.shadowLogged = false;
            }
        }
        if (!route.registered) {
            try {
                registry.registerRemote(route.profile, route);
                route.registered = true;
                route.shadowLogged = false;
            } catch (IllegalArgumentException e) {
                if (!route.shadowLogged) {
                    route.shadowLogged = true;
                    // A local component always wins over a route, by design; it happens on every
                    // migration (the target registers before the source withdraws), so not a warning.
                    log.info("profile '{}' announced by node '{}' is registered on this node already; this node's"
                            + " registration wins ({})", route.profile, first.nodeId, e.getMessage());
                }
            }
        }
    }

    /**
     * A departed profile's wait is over: if still no node announces it, it is unrouted, and what
     * was held for it is reported undeliverable to its senders.
     */
    private synchronized void expireDeparted(ProfileRoute route, long departure) {
        if (routes.get(route.profile) == route && route.hosts.isEmpty() && route.order.isDeparted(departure)) {
            log.info("profile '{}' was withdrawn and no node announced it within {} ms: unrouted", route.profile,
                    TimeUnit.NANOSECONDS.toMillis(RouteFlushes.FLUSH_WAIT_NS));
            sync(route, true); // unregisters it; what was held is sent again or reported
        }
    }

    /** The messenger closes: profiles still waiting for their next host are unrouted now. */
    synchronized void close() {
        closing = true;
        for (ProfileRoute route : List.copyOf(routes.values())) {
            if (route.hosts.isEmpty()) {
                sync(route);
            }
        }
    }

    private void schedule(Runnable task) {
        try {
            control.schedule(task, RouteFlushes.FLUSH_WAIT_NS, TimeUnit.NANOSECONDS);
        } catch (RejectedExecutionException e) {
            // The messenger is closing: the routes go with it.
        }
    }

    private boolean isRegistered(ProfileRoute route) {
        try {
            return registry.resolve(route.profile) instanceof Endpoint.Remote remote && remote.route() == route;
        } catch (ProfileResolutionException e) {
            return false;
        }
    }
}
