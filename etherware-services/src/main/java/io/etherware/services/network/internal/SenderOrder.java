package io.etherware.services.network.internal;

import io.etherware.core.message.Message;
import java.util.ArrayDeque;
import java.util.ArrayList;
import java.util.List;
import java.util.concurrent.atomic.AtomicInteger;
import java.util.concurrent.atomic.AtomicIntegerArray;
import java.util.concurrent.locks.LockSupport;

/**
 * The order of this node's messages to one remote profile when the node hosting it changes (a
 * migration, see {@code io.etherware.services.management}). Messages this node sent to the old
 * host may still be on their way there, to be forwarded; one sent straight to the new host could
 * overtake them. So when the owner of a {@link RouteTable.ProfileRoute} changes, each lane this
 * node used for the profile since the last change is <em>held</em>: an
 * {@link io.etherware.core.kernel.OrderMarker} goes to the profile through the old host, behind
 * those messages (a lane's stream is FIFO at every hop, and the marker is the least critical
 * message of its lane, so every queue on the way puts it behind each earlier one), and travels on
 * as they do, forwarded by the old host. The lane's later messages wait here until the kernel
 * that finds the component hosted answers the marker: everything this node sent it before is
 * queued there, and that kernel keeps their order before anything sent later, through holds and
 * moves. They then go in the order they were sent. A lane this node has not used since the last
 * change is never held: nothing of it can be on the way. While no node announces the profile after
 * its host withdrew it ({@link #departed}), every message to it is held.
 *
 * <p>A marker unanswered within {@link RouteFlushes#FLUSH_WAIT_NS} (the old host died or dropped
 * it) releases the lane anyway, logged: what the old host had is lost with it, and waiting longer
 * would only delay the rest. A marker the old host cannot take at all (it is gone) releases the
 * lane at once.
 *
 * <p>Thread-safety: {@link #deliver} from any sending thread, lock-free unless a lane is held; the
 * change of owner, the markers and their answers are serialized on this object. The change of
 * owner happens on this object's monitor, and a marker is sent only once every send that read the
 * old owner has finished handing its message to it (an epoch count), so no message to the old
 * host can slip in behind the marker.
 */
final class SenderOrder {

    /** A lane's state; guarded by the order. */
    private static final class Lane {
        /** The old host the marker goes through; null while the lane is not held. */
        Peer via;
        /** The marker's token; 0 until the marker is sent. */
        long token;
        final ArrayDeque<Message> held = new ArrayDeque<>();
    }

    private final RouteTable.ProfileRoute route;
    private final RouteFlushes flushes;
    /** Lanes this node sent the profile's messages on since the owner last changed, a bit each. */
    private final AtomicInteger used = new AtomicInteger();
    private final AtomicInteger epoch = new AtomicInteger();
    /** Sends in progress, by the parity of the epoch they began in. */
    private final AtomicIntegerArray sending = new AtomicIntegerArray(2);
    /** Whether a lane may be held: the sends' only read of this object's state in the common case. */
    private volatile boolean holding;
    /** The host that withdrew the profile while no other announced it; guarded by this. */
    private Peer departedFrom;
    /** Departures so far, so that the end of a wait applies to its own departure only; guarded by this. */
    private long departures;
    private final Lane[] lanes;

    SenderOrder(RouteTable.ProfileRoute route, RouteFlushes flushes) {
        this.route = route;
        this.flushes = flushes;
        this.lanes = new Lane[flushes.laneCount()];
        for (int i = 0; i < lanes.length; i++) {
            lanes[i] = new Lane();
        }
    }

    /**
     * Sends {@code message} to the route's owner now, or holds it: behind its lane's marker, or
     * until a node announces the profile again after its host withdrew it.
     */
    void deliver(Message message) {
        int lane = flushes.laneOf(message);
        int bit = 1 << lane;
        if ((used.get() & bit) == 0) {
            used.getAndAccumulate(bit, (a, b) -> a | b); // before the owner is read: see ownerChanged
        }
        int slot = epoch.get() & 1;
        sending.incrementAndGet(slot);
        try {
            Peer to = route.owner;
            if (holding && held(lane, message)) {
                return;
            }
            if (to == null) {
                throw new IllegalStateException("no connected node announces '" + route.profile + "' now");
            }
            to.enqueue(message);
        } finally {
            sending.decrementAndGet(slot);
        }
    }

    private synchronized boolean held(int lane, Message message) {
        Lane state = lanes[lane];
        if (state.via == null) {
            if (departedFrom == null) {
                return false;
            }
            state.via = departedFrom; // its marker goes when the next host announces the profile
            state.token = 0;
        }
        state.held.add(message);
        return true;
    }

    /**
     * The route's owner changes from {@code from} to {@code to} (the route table's lock is held;
     * {@code from} is null if the profile had departed, see {@link #departed}). Holds every lane
     * used since the last change, and returns the task that sends the markers of the held lanes,
     * to run off the table's lock; null if there are none to send.
     */
    Runnable ownerChanged(Peer from, Peer to) {
        boolean toSend = false;
        synchronized (this) {
            holding = true; // before the owner: a send that sees the new owner takes the slow path
            route.owner = to;
            Peer via = from != null ? from : departedFrom;
            departedFrom = null;
            int mask = used.getAndSet(0); // a send that set its bit after this sees the new owner
            for (int lane = 0; lane < lanes.length; lane++) {
                Lane state = lanes[lane];
                if ((mask & (1 << lane)) != 0 && state.via == null && via != null) {
                    state.via = via;
                    state.token = 0;
                }
                toSend |= state.via != null && state.token == 0;
            }
            holding = anyHeld();
        }
        return toSend ? this::sendMarkers : null;
    }

    /**
     * The last node announcing the profile, {@code from}, withdrew it (the route table's lock is
     * held): a migration's source does so when its component has left, and the target's
     * announcement, on another connection, may come a little later. Until it comes (see
     * {@link #ownerChanged}) or the route table gives up ({@link #abandon}), every message is
     * held; the lanes used through {@code from} will need a marker through it.
     *
     * @return this departure's number, for {@link #isDeparted(long)}
     */
    synchronized long departed(Peer from) {
        holding = true;
        route.owner = null;
        departedFrom = from;
        departures++;
        int mask = used.getAndSet(0);
        for (int lane = 0; lane < lanes.length; lane++) {
            if ((mask & (1 << lane)) != 0 && lanes[lane].via == null) {
                lanes[lane].via = from;
                lanes[lane].token = 0;
            }
        }
        return departures;
    }

    /** Whether the profile departed and no node announced it since. */
    synchronized boolean isDeparted() {
        return departedFrom != null;
    }

    /** Whether the profile is still in the departure {@code departure} ({@link #departed} returned it). */
    synchronized boolean isDeparted(long departure) {
        return departedFrom != null && departures == departure;
    }

    /** No node announced the profile in time: ends every hold; returns the held messages, to report. */
    synchronized List<Message> abandon() {
        departedFrom = null;
        var left = new ArrayList<Message>();
        for (Lane state : lanes) {
            left.addAll(open(state));
        }
        holding = false;
        return left;
    }

    /**
     * Waits until every send that may have read the old owner has handed its message over, then
     * sends a marker on each held lane that has none yet (none while the profile has departed:
     * they go when the next host is known).
     */
    private void sendMarkers() {
        int old = epoch.getAndIncrement() & 1;
        long deadline = System.nanoTime() + RouteFlushes.DRAIN_WAIT_NS;
        while (sending.get(old) > 0 && System.nanoTime() < deadline) {
            LockSupport.parkNanos(20_000);
        }
        if (sending.get(old) > 0) {
            flushes.drainTimedOut(route.profile);
        }
        List<Runnable> reports;
        synchronized (this) {
            if (departedFrom != null) {
                return;
            }
            var released = new ArrayList<Message>();
            for (int lane = 0; lane < lanes.length; lane++) {
                Lane state = lanes[lane];
                if (state.via != null && state.token == 0) {
                    state.token = flushes.sendMarker(this, lane, route.profile, state.via);
                    if (state.token == 0) {
                        released.addAll(open(state)); // the old host is gone for good: nothing to wait for
                    }
                }
            }
            reports = flushes.deliverReleased(route, released);
            holding = anyHeld();
        }
        reports.forEach(Runnable::run);
    }

    /**
     * The marker with {@code token} was answered or given up on: releases its lane's held
     * messages, in order, to the current owner (while the profile has departed, they stay held
     * for the next host, behind a new marker). False if the token is not this lane's marker (any
     * more).
     */
    boolean release(int lane, long token) {
        List<Runnable> reports;
        synchronized (this) {
            Lane state = lanes[lane];
            if (state.token != token || state.via == null) {
                return false;
            }
            if (departedFrom != null) {
                state.token = 0;
                return true;
            }
            // Under the monitor, and before the sends may skip it, so they go after these.
            reports = flushes.deliverReleased(route, open(state));
            holding = anyHeld();
        }
        reports.forEach(Runnable::run); // what could not be handed over, reported off the monitor
        return true;
    }

    private List<Message> open(Lane state) {
        var release = new ArrayList<>(state.held);
        state.held.clear();
        state.via = null;
        state.token = 0;
        return release;
    }

    private boolean anyHeld() {
        for (Lane lane : lanes) {
            if (lane.via != null) {
                return true;
            }
        }
        return false;
    }

}
