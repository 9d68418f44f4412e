package io.etherware.services.network.internal;

import io.etherware.core.kernel.Endpoint;
import io.etherware.core.kernel.ProfileRegistry;
import io.etherware.core.kernel.ProfileResolutionException;
import io.etherware.core.kernel.RemoteRoute;
import io.etherware.core.message.Message;
import io.etherware.core.message.Profile;
import java.util.HashMap;
import java.util.HashSet;
import java.util.List;
import java.util.Map;
import java.util.Set;
import java.util.TreeMap;
import org.slf4j.Logger;
import org.slf4j.LoggerFactory;

/**
 * The profiles other nodes announced, and the {@link RemoteRoute}s registered for them in this
 * node's registry so that {@code send} to such a profile reaches the node hosting it.
 *
 * <p>Conflicts are resolved the same way on every node: a local component wins over any
 * announcement (the registry refuses the route, and a component added later displaces it); among
 * remote nodes announcing the same profile, the lowest node id wins. Both are logged.
 *
 * <p>Thread-safety: changes are serialized on this object. Lock order: this, then the registry
 * (whose listener must therefore never call back in here; the messenger queues such work).
 */
final class RouteTable {

    private static final Logger log = LoggerFactory.getLogger(RouteTable.class);

    private final ProfileRegistry registry;
    private final Map<Profile, ProfileRoute> routes = new HashMap<>();
    private final Map<String, Set<Profile>> byPeer = new HashMap<>();

    RouteTable(ProfileRegistry registry) {
        this.registry = registry;
    }

    /** The route to one remote profile: it follows whichever node currently hosts it. */
    static final class ProfileRoute implements RemoteRoute {
        final Profile profile;
        /** Nodes announcing the profile, by id; guarded by the table. */
        final TreeMap<String, Peer> hosts = new TreeMap<>();
        volatile Peer owner;
        /** Whether the registry holds this route; guarded by the table. */
        boolean registered;
        boolean shadowLogged;

        ProfileRoute(Profile profile) {
            this.profile = profile;
        }

        @Override
        public void deliver(Message message) {
            Peer to = owner;
            if (to == null) {
                throw new IllegalStateException("no connected node announces '" + profile + "' now");
            }
            to.enqueue(message);
        }

        @Override
        public String toString() {
            Peer to = owner;
            return "network route to '" + profile + "' on node '" + (to == null ? "?" : to.nodeId) + "'";
        }
    }

    /** {@code peer} hosts exactly {@code profiles} now (an ANNOUNCE replaces the previous one). */
    synchronized void announce(Peer peer, List<Profile> profiles) {
        Set<Profile> now = new HashSet<>(profiles);
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
                ProfileRoute route = routes.computeIfAbsent(profile, ProfileRoute::new);
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

    /** The peer is gone for good (grace expired, or the messenger closes): unroute its profiles. */
    synchronized void forget(Peer peer) {
        announce(peer, List.of());
    }

    /** The registry changed for {@code profile} under our feet (a local component came or went). */
    synchronized void reconcile(Profile profile) {
        ProfileRoute route = routes.get(profile);
        if (route != null) {
            route.registered = isRegistered(route);
            sync(route);
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
        if (route.hosts.isEmpty()) {
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
            return;
        }
        Peer first = route.hosts.firstEntry().getValue();
        if (route.owner != first) {
            if (route.hosts.size() > 1) {
                log.warn("profile '{}' is announced by nodes {}: routing to '{}', the lowest node id", route.profile,
                        route.hosts.keySet(), first.nodeId);
            }
            route.owner = first;
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

    private boolean isRegistered(ProfileRoute route) {
        try {
            return registry.resolve(route.profile) instanceof Endpoint.Remote remote && remote.route() == route;
        } catch (ProfileResolutionException e) {
            return false;
        }
    }
}
