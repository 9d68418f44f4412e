package io.etherware.services.network.internal;

import io.etherware.core.kernel.Endpoint;
import io.etherware.core.kernel.Kernel;
import io.etherware.core.kernel.ProfileRegistry;
import io.etherware.core.kernel.ProfileResolutionException;
import io.etherware.core.kernel.RemoteRoute;
import io.etherware.core.kernel.RouteMarker;
import io.etherware.core.message.Message;
import io.etherware.core.message.MessageId;
import io.etherware.core.message.Profile;
import io.etherware.core.message.QoS;
import io.etherware.services.network.AnnouncePolicy;
import java.lang.invoke.MethodHandles;
import java.lang.invoke.VarHandle;
import java.util.ArrayDeque;
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
import java.util.concurrent.locks.LockSupport;
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
 * the route (and relays) until it withdraws the profile, then the target has it.
 *
 * <p>When the node a route leads to changes while this node sends through it (a migration moved
 * the component), the route holds its messages until a {@link RouteMarker} sent through the old
 * node has reached the component, so none overtakes one sent earlier through the old node
 * (NETWORK-PROTOCOL.md, "Route moves").
 *
 * <p>Thread-safety: changes are serialized on this object. Lock order: this, then the registry
 * (whose listener must therefore never call back in here; the messenger queues such work); this,
 * then a {@link Move}, then a link's lock (a move's end). A sender takes a move's lock alone, and
 * only while its route moves.
 */
final class RouteTable {

    private static final Logger log = LoggerFactory.getLogger(RouteTable.class);

    private static final String NODE_ROLE = "etherware.node";
    /**
     * How long a moving route waits for its marker's answer (a round trip through the old node and
     * the new one, a few milliseconds on a LAN) before it sends its held messages on anyway.
     */
    static final long MOVE_WAIT_NS = TimeUnit.MILLISECONDS.toNanos(500);
    /** How long the marker waits for the senders already inside the route to finish. */
    private static final long QUIET_WAIT_NS = TimeUnit.MILLISECONDS.toNanos(10);
    private static final long QUIET_POLL_NS = TimeUnit.MICROSECONDS.toNanos(20);

    private final ProfileRegistry registry;
    private final AnnouncePolicy policy;
    private final LongAdder refused;
    private final Map<Profile, ProfileRoute> routes = new HashMap<>();
    private final Map<String, Set<Profile>> byPeer = new HashMap<>();
    /** A route a migration registered, to be replaced by the announced route once it leads there. */
    private record Provisional(RemoteRoute route, String nodeId) {
    }

    /** The routes migrations registered, by profile, until the announced route takes over. */
    private final Map<Profile, Provisional> provisional = new HashMap<>();
    /** The routes that wait for their marker, by the marker's id. */
    private final Map<MessageId, ProfileRoute> moving = new HashMap<>();
    private final Kernel kernel;
    private final ScheduledExecutorService control;
    private final Losses losses;
    private final int holdCapacity;
    private final LongAdder moves;
    private final LongAdder movesUnconfirmed;
    private long refusalsLogged;

    /**
     * @param counters     counts the announced profiles refused and the routes that moved
     * @param control      the messenger's control thread: sends markers, ends waits that last too long
     * @param holdCapacity how many messages a moving route holds at most (the queue capacity)
     */
    RouteTable(Kernel kernel, AnnouncePolicy policy, Counters counters, ScheduledExecutorService control,
               Losses losses, int holdCapacity) {
        this.kernel = kernel;
        this.registry = kernel.registry();
        this.policy = policy;
        this.refused = counters.announcementsRefused;
        this.moves = counters.routeMoves;
        this.movesUnconfirmed = counters.routeMovesUnconfirmed;
        this.control = control;
        this.losses = losses;
        this.holdCapacity = holdCapacity;
    }

    /**
     * The route to one remote profile: it follows whichever node currently hosts it. When that
     * node changes from one connected node to another, the messages for the profile wait in a
     * {@link Move} until a marker sent through the old node has reached the component (see
     * {@link #startMove}); the ordinary path adds a counter of the senders in it and a volatile
     * read, and takes no lock.
     */
    static final class ProfileRoute implements RemoteRoute {
        private static final VarHandle SENDING;

        static {
            try {
                SENDING = MethodHandles.lookup().findVarHandle(ProfileRoute.class, "sending", int.class);
            } catch (ReflectiveOperationException e) {
                throw new ExceptionInInitializerError(e);
            }
        }

        final Profile profile;
        /** Nodes announcing the profile, in the order they claimed it; guarded by the table. */
        final LinkedHashMap<String, Peer> hosts = new LinkedHashMap<>();
        /** Where messages go; written under the table's lock, after {@link #move} when a move starts. */
        volatile Peer owner;
        /** The move in progress, or null; written under the table's lock. */
        volatile Move move;
        /** Senders inside {@link #deliver}: a marker goes once none can still hand a message to the old node. */
        @SuppressWarnings("unused") // through SENDING
        private volatile int sending;
        /** The ids of {@link #hosts}, for readers outside the table's lock. */
        volatile Set<String> hostIds = Set.of();
        /** Whether the registry holds this route; guarded by the table. */
        boolean registered;
        boolean shadowLogged;

        ProfileRoute(Profile profile) {
            this.profile = profile;
        }

        @Override
        public void deliver(Message message) {
            SENDING.getAndAdd(this, 1);
            try {
                // The owner before the move: a move publishes itself before its new owner, so a
                // sender that sees the new owner sees the move (or its end) too.
                Peer to = owner;
                Move moving = move;
                while (moving != null) {
                    if (moving.hold(message)) {
                        return;
                    }
                    // That move ended, its held messages sent first; another may have begun since.
                    to = owner;
                    Move next = move;
                    moving = next == moving ? null : next;
                }
                if (to == null) {
                    throw new IllegalStateException("no connected node announces '" + profile + "' now");
                }
                to.enqueue(message);
            } finally {
                SENDING.getAndAdd(this, -1);
            }
        }

        /** Whether no sender is inside {@link #deliver} now. */
        boolean isQuiet() {
            return (int) SENDING.getVolatile(this) == 0;
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
                ProfileRoute route = routes.computeIfAbsent(profile, ProfileRoute::new);
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
        announce(peer, List.of());
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
        route.hostIds = Set.copyOf(route.hosts.keySet());
        if (route.hosts.isEmpty()) {
            route.owner = null;
            endMove(route, "no connected node announces '" + route.profile + "' now");
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
            Peer was = route.owner;
            Move moving = route.move;
            if (moving == null && was != null && route.registered && was.isConnected()) {
                startMove(route, was);
            }
            route.owner = first;
            if (moving != null && first.nodeId.equals(moving.reachedAt)) {
                endMove(route, null); // the marker reached the component at the node the route now leads to
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
     * The route's node changes from {@code was} to another while this node sends through it: its
     * messages sent through {@code was} may still be on their way there (or queued there), and
     * {@code was} forwards them to the component, so a later message sent to the new node directly
     * could overtake them. The route therefore holds its messages from now on, and once no sender
     * can still hand one to {@code was}, sends a {@link RouteMarker} to the profile through
     * {@code was}, at NONE criticality (after every message queued for {@code was} before it, on
     * every lane). {@code was} forwards it behind them; the node where it reaches the component
     * answers it ({@link #markerReached}), and the held messages go to the route's node then, ahead
     * of any later one. A marker that is not answered within {@link #MOVE_WAIT_NS} (the old node
     * died, or dropped it) ends the wait anyway, logged: the held messages go on, and only a message
     * still on its way through the old node can then come after a later one.
     */
    private void startMove(ProfileRoute route, Peer was) {
        var move = new Move(route, was, kernel.newMessageId(), holdCapacity);
        moves.increment();
        route.move = move; // before the new owner (see ProfileRoute.deliver)
        moving.put(move.markerId, route);
        try {
            control.execute(() -> sendMarker(move));
            control.schedule(() -> expire(move), MOVE_WAIT_NS, TimeUnit.NANOSECONDS);
        } catch (RejectedExecutionException e) {
            endMove(route, null); // the messenger is closing
        }
    }

    /** Control thread: sends the move's marker through the old node once no sender can still reach it. */
    private void sendMarker(Move move) {
        long untilNs = System.nanoTime() + QUIET_WAIT_NS;
        while (!move.route.isQuiet() && System.nanoTime() < untilNs) {
            LockSupport.parkNanos(QUIET_POLL_NS);
        }
        synchronized (this) {
            if (move.route.move != move) {
                return;
            }
            try {
                move.through.enqueue(new Message(move.route.profile, kernel.profile(), kernel.clock().epochNanos(),
                        QoS.NONE, new RouteMarker(false), move.markerId, null));
            } catch (RuntimeException e) {
                log.warn("profile '{}': the route marker through node '{}' was refused ({}); sending on without it",
                        move.route.profile, move.through.nodeId, e.toString());
                movesUnconfirmed.increment();
                endMove(move.route, null);
            }
        }
    }

    /**
     * A node answered a marker of this node's: it reached the component there, behind everything
     * this node sent the profile through the old node, so the held messages go on to the route's
     * node now. An answer to no pending marker (late, or not ours) is ignored.
     */
    synchronized void markerReached(Message answer) {
        ProfileRoute route = moving.get(answer.correlationId());
        Move move = route == null ? null : route.move;
        if (move == null || !move.markerId.equals(answer.correlationId()) || answer.origin() == null) {
            return;
        }
        String at = answer.origin().nodeId();
        log.debug("profile '{}': route marker answered by node '{}' after {} us; {} held messages, the route leads to"
                + " node '{}'", route.profile, at, (System.nanoTime() - move.startNs) / 1000, move.held(),
                route.owner == null ? "?" : route.owner.nodeId);
        if (route.owner != null && route.owner.nodeId.equals(at) || !route.hosts.containsKey(at)) {
            // There, or at a node that has given the component up since: its relocation carried
            // what this node sent before the marker, ahead of anything it receives later.
            endMove(route, null);
        } else {
            // At a node that installed the component and waits to take the route over (the node
            // that hosts it now is relocating it there): held messages sent on to the present node
            // would reach it through that relocation, ahead of the older ones it queued itself.
            move.reachedAt = at;
        }
    }

    /** The marker was not answered in time. */
    private synchronized void expire(Move move) {
        if (move.route.move == move) {
            movesUnconfirmed.increment();
            log.warn("profile '{}': no answer to the route marker through node '{}' within {} ms; sending the {}"
                    + " held messages on to node '{}' (one still on its way through node '{}' may come after them)",
                    move.route.profile, move.through.nodeId, TimeUnit.NANOSECONDS.toMillis(MOVE_WAIT_NS),
                    move.held(), move.route.owner == null ? "?" : move.route.owner.nodeId, move.through.nodeId);
            endMove(move.route, null);
        }
    }

    /**
     * Ends the route's move, if any: its held messages go to the route's node in order (or are
     * reported undeliverable with {@code lostReason} if there is none), then senders go there
     * directly.
     */
    private void endMove(ProfileRoute route, String lostReason) {
        Move move = route.move;
        if (move == null) {
            return;
        }
        moving.remove(move.markerId);
        move.end(route.owner, lostReason, losses);
        route.move = null;
    }

    /**
     * The messages a route holds while it moves. {@link #hold} from any sender; {@link #end} under
     * the table's lock. Guarded by this object.
     */
    static final class Move {
        final ProfileRoute route;
        final Peer through;
        final MessageId markerId;
        private final int capacity;
        final long startNs = System.nanoTime();
        /** The node where the marker reached the component, if the route did not lead there then; guarded by the table. */
        String reachedAt;
        private final ArrayDeque<Message> held = new ArrayDeque<>();
        private boolean ended;

        Move(ProfileRoute route, Peer through, MessageId markerId, int capacity) {
            this.route = route;
            this.through = through;
            this.markerId = markerId;
            this.capacity = capacity;
        }

        /** Keeps {@code message} for later; false if the move has ended (send it on directly). */
        synchronized boolean hold(Message message) {
            if (ended) {
                return false;
            }
            if (held.size() >= capacity) {
                throw new IllegalStateException("the route to '" + route.profile + "' holds " + held.size()
                        + " messages while it moves to another node (at most the queue capacity)");
            }
            held.add(message);
            return true;
        }

        synchronized int held() {
            return held.size();
        }

        /** Sends the held messages on to {@code to}, in order; from now on senders send there. */
        synchronized void end(Peer to, String lostReason, Losses losses) {
            ended = true;
            Message message;
            while ((message = held.poll()) != null) {
                if (to == null) {
                    losses.lost(message, lostReason);
                    continue;
                }
                try {
                    to.enqueue(message);
                } catch (RuntimeException e) {
                    losses.lost(message, "the route to '" + route.profile + "' refused it: " + e.getMessage());
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
