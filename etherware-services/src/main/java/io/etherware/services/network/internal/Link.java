package io.etherware.services.network.internal;

import io.etherware.core.message.Message;
import io.etherware.services.network.CloseReason;
import java.io.IOException;
import java.util.ArrayList;
import java.util.List;
import java.util.concurrent.locks.Condition;
import java.util.concurrent.locks.ReentrantLock;
import java.util.function.Supplier;

/**
 * One lane to another node, across connections: the messages waiting for it (by criticality),
 * the messages written but not yet acknowledged, where both streams stand, and which connection
 * is the one in use. A {@link Peer} has one link per lane; each lane is a connection of its own
 * with its own streams, so a lane's messages never wait behind another lane's bytes.
 *
 * <p>Streams. Messages to a peer are numbered in a stream with a random id; the peer
 * acknowledges how many of them its kernel has. A new connection to the same peer resumes the
 * stream: what the peer already has is released, the rest is written again and duplicates are
 * dropped by number, so nothing is lost or delivered twice while both nodes live. If the peer
 * does not know the stream (it restarted), the unacknowledged messages are reported to their
 * senders as undeliverable and numbering starts over.
 *
 * <p>Parts. The link owns the connection in use and the lock, and coordinates its parts, each
 * given what it needs when the link is made: {@link OutboundRules} (hops, encoding and overflow,
 * on the sender's thread), {@link Outbox} (the waiting messages and what a writer's turn takes),
 * {@link OutboundStream} and {@link InboundStream} (the two streams), {@link Resumption} (how they
 * carry on over a new connection), {@link LaneOrder} (the NONE ordering across lanes),
 * {@link OutputToken} (who writes: the writer thread or a sender directly) and {@link LaneLife}
 * (whether the lane takes messages).
 *
 * <p>Locking: {@link #lock} guards the outbound state (the parts above) and the connections'
 * writer requests; the {@link #inbound} stream's monitor guards it and is taken first when both
 * are needed. The parts take no lock of their own ({@link OutputToken#release} takes this one).
 * Nothing calls the kernel while holding {@link #lock}. Lane 0's reader, after an acknowledgement
 * and with no lock held, only tries lane 1's lock ({@link #nudge}); it never waits for it.
 */
final class Link {

    final String nodeId;
    /** Which lane of the peer this is. */
    final int lane;
    final ReentrantLock lock = new ReentrantLock();
    /** Signalled when a writer may have work: messages, acknowledgements, control requests. */
    final Condition work = lock.newCondition();
    /** The peer's stream to this node on this lane. */
    private final InboundStream inbound = new InboundStream();

    private final NetworkContext context;
    private final OutboundRules rules;
    /** Lane 1's link, nudged when an acknowledgement here may let its held NONE message go; set once. */
    volatile Link follower;
    /**
     * This lane's writer has a NONE message that waits for lane 0 at the head of its queue: set
     * before the writer looks whether lane 0 settled it, cleared once it may go.
     */
    private volatile boolean holdsNone;
    /** Lane 0 settled messages since this lane's writer last looked (see {@link #nudge}). */
    private volatile boolean nudged;
    private volatile Connection active;

    // Guarded by lock.
    /** The NONE ordering across lanes. */
    private final LaneOrder order;
    /** This node's stream to the peer on this lane. */
    private final OutboundStream out;
    /** The messages waiting for the writer. */
    private final Outbox outbox;
    private final Resumption resumption;
    /** Who owns the active connection's output: the writer thread, or a sender writing directly. */
    private final OutputToken token = new OutputToken(lock, work);
    private final LaneLife life;

    Link(String nodeId, int lane, NetworkContext context, Link precedent) {
        this.nodeId = nodeId;
        this.lane = lane;
        this.context = context;
        this.rules = new OutboundRules(nodeId, context);
        var generations = new Generations();
        this.order = new LaneOrder(generations, precedent == null ? null : precedent.order);
        this.out = new OutboundStream(context.lanes().size() == 1, generations);
        this.outbox = new Outbox(context.config().queueCapacity(), order, out);
        this.resumption = new Resumption(out, inbound);
        this.life = new LaneLife(nodeId, context);
    }

    // ---------------------------------------------------------------- sending

    /**
     * Takes a message for this peer without ever blocking. When the connection is idle (nothing
     * queued, nothing being written, little unacknowledged) the calling thread encodes and writes
     * it itself: the socket's buffer has room for it (everything acknowledged has left it), and a
     * thread hand-off is saved. Otherwise the message is queued for the writer: a full queue
     * evicts a less critical message or, when there is none, drops a NONE or LOW message
     * (counted) or refuses a MIDDLE or HIGH one by throwing, which the kernel turns into an
     * undeliverable notice to its sender.
     */
    void enqueue(Message message, long after) {
        int hops = rules.hops(message);
        Connection direct = active;
        // Encoded here, on the sender's thread: its size counts against the peer's byte bound.
        byte[] xml = rules.encode(message, direct);
        OutboundQueue.Outcome outcome = null;
        InFlight written = null;
        lock.lock();
        try {
            life.checkTakesMessages();
            long maxBytes = context.config().maxQueuedBytesPerPeer();
            var outgoing = new Outgoing(message, hops, xml, after, order.take());
            if (direct != null && active == direct && !token.isHeld()
                    && outbox.mayGoDirectly(outgoing, direct, context.config().windowMessages(), maxBytes)) {
                token.hold(true);
                written = out.add(outgoing);
            } else {
                outcome = outbox.offer(outgoing, maxBytes);
                if (!(outcome instanceof OutboundQueue.Outcome.Full)) {
                    work.signal();
                }
            }
        } finally {
            lock.unlock();
        }
        if (written != null) {
            writeDirect(direct, written);
            return;
        }
        rules.overflowed(message, outcome);
    }

    private void writeDirect(Connection connection, InFlight entry) {
        try {
            connection.output().writeDirect(entry);
        } catch (IOException e) {
            // Kept in flight: the next connection sends it again, or its sender hears it is lost.
            context.closeLater(connection, CloseReason.IO_ERROR, "writing to node '" + nodeId + "' failed: " + e);
        } finally {
            endTurn();
        }
    }

    /** Whoever owned the output gives it back; a writer waiting for it may take its turn. */
    void endTurn() {
        token.release();
    }

    // ---------------------------------------------------------------- connections

    /** Where this node's streams with the peer stand, for the RESUME frame. */
    Frame.Resume resumeState() {
        synchronized (inbound) {
            lock.lock();
            try {
                return new Frame.Resume(out.streamId(), inbound.streamId(), inbound.count());
            } finally {
                lock.unlock();
            }
        }
    }

    /**
     * Makes {@code candidate}, handshaken, this peer's connection, unless a connection that wins
     * the one-connection rule is already in use. Resumes or restarts both streams (see
     * {@link Resumption#resume}).
     */
    LaneActivation activate(Connection candidate, Frame.Resume theirs, Supplier<byte[]> announceBody) {
        synchronized (inbound) {
            lock.lock();
            try {
                if (!life.mayConnect()) {
                    return new LaneActivation(false, candidate, List.of(), null);
                }
                LaneActivation activation = resumption.resume(active, candidate, theirs);
                if (!activation.accepted()) {
                    return activation;
                }
                active = candidate;
                life.connected();
                out.restartClock();
                // Read under the lock: an announcement published meanwhile finds this connection active.
                candidate.requests.announce(announceBody.get());
                work.signalAll();
                return activation;
            } finally {
                lock.unlock();
            }
        }
    }

    /**
     * The connection ends: if it was this peer's, the peer is down from now on (its messages wait
     * for a new connection, for at most the grace period).
     */
    boolean deactivate(Connection connection) {
        lock.lock();
        try {
            if (active != connection) {
                return false;
            }
            active = null;
            life.down();
            work.signalAll();
            return true;
        } finally {
            lock.unlock();
        }
    }

    Connection active() {
        return active;
    }

    boolean isConnected() {
        return active != null;
    }

    // ---------------------------------------------------------------- the writer's side

    /**
     * What a writer does in one turn; null when it should stop. Blocks until there is work or a
     * heartbeat is due.
     */
    WriterTurn nextTurn(Connection connection, int batch) throws InterruptedException {
        int window = context.config().windowMessages();
        lock.lock();
        try {
            while (true) {
                if (active != connection) {
                    if (token.isHeld()) {
                        token.await();
                        continue;
                    }
                    WriterTurn last = connection.requests.takeBye();
                    token.hold(last != null);
                    return last;
                }
                Outgoing head = outbox.peek();
                // Announced before the look at lane 0, and the nudge cleared: a settlement that
                // this look misses sees the announcement and nudges (see nudge()).
                holdsNone = head != null && head.after() >= 0;
                nudged = false;
                boolean held = head != null && !order.mayGo(head);
                holdsNone = held;
                boolean sendable = head != null && out.size() < window && out.lowRoomFor(head, 0) && !held;
                if (!connection.requests.hasRequests() && !sendable) {
                    long waitNs = connection.output().heartbeatDueNs() - NetworkContext.nowNs();
                    if (waitNs > 0) {
                        if (held && nudged) {
                            continue; // lane 0 settled since the look: look again
                        }
                        work.awaitNanos(LaneOrder.waitNs(waitNs, held));
                        continue;
                    }
                    connection.requests.requestHeartbeat();
                }
                if (token.isHeld()) {
                    token.await(); // a sender is writing directly; it signals when done
                    continue;
                }
                break;
            }
            WriterTurn turn = connection.requests.takeRequests(batch);
            // New messages only once every message to send again is out: the peer expects the
            // stream in order.
            int room = connection.requests.mustPrecedeMessages() ? 0 : Math.min(batch, window - out.size());
            outbox.fill(turn, room);
            token.hold(true);
            return turn;
        } finally {
            lock.unlock();
        }
    }

    /**
     * Numbers the encoded messages of a turn and keeps them until acknowledged; null if the
     * connection is no longer the peer's, in which case they go back to the front of the queue.
     * {@code givenUp} are messages of the turn that cannot go (reported lost by the caller).
     */
    List<InFlight> assign(Connection connection, List<Outgoing> encoded, List<Outgoing> givenUp) {
        lock.lock();
        try {
            givenUp.forEach(order::settle);
            if (active != connection) {
                outbox.pushBack(encoded);
                work.signalAll();
                return null;
            }
            var assigned = new ArrayList<InFlight>(encoded.size());
            for (Outgoing outgoing : encoded) {
                assigned.add(out.add(outgoing));
            }
            return assigned;
        } finally {
            lock.unlock();
        }
    }

    /**
     * Closes this lane's open generation for a NONE message of lane 1 queued now (see {@link
     * Peer#enqueue}): it goes once every message taken here before it is settled.
     */
    long closeGeneration() {
        lock.lock();
        try {
            long closed = order.close();
            if (order.awaitSync(closed)) {
                // Its messages are settled when the peer acknowledges them, which it may put off
                // for up to 10 ms: a SYNC after them asks it to at once.
                Connection connection = active;
                if (connection != null) {
                    connection.requests.requestSync();
                    work.signal();
                }
            }
            return closed;
        } finally {
            lock.unlock();
        }
    }

    /**
     * How long the peer has read nothing of what was written to it: no acknowledgement progress
     * while messages are in flight, or a write of the active connection blocked.
     */
    long unreadForNs(long nowNs) {
        Connection connection = active;
        long since = out.unackedSinceNs();
        long unacked = since == 0 ? 0 : nowNs - since;
        return Math.max(unacked, connection == null ? 0 : connection.output().writeBlockedForNs(nowNs));
    }

    /** The peer's kernel has the first {@code count} messages of the stream. */
    void onAck(Connection connection, long count) throws ProtocolException {
        if (count == out.ackedCount()) {
            return;
        }
        List<InFlight> lost;
        String error;
        lock.lock();
        try {
            if (active != connection || count == out.ackedCount()) {
                return;
            }
            error = out.ackContradiction(count);
            if (error != null) {
                lost = out.reset();
            } else {
                error = null;
                lost = List.of();
                acknowledged(connection, count);
            }
        } finally {
            lock.unlock();
        }
        if (error != null) {
            // Reported once the connection is closed: notices to the peer then wait for the next one.
            throw new StreamResetException(error, lost);
        }
        Link waiting = follower;
        if (waiting != null) {
            waiting.nudge();
        }
    }

    /**
     * Lane 0 settled messages: if this lane's writer holds a NONE message for it, it looks again
     * now rather than at its next 1 ms poll. Never blocks: the caller is lane 0's reader, which
     * must not wait for this lane's lock (held by LOW senders and this lane's writer). It sets
     * {@link #nudged}, which the writer reads between its look and its wait, and signals the writer
     * if the lock is free. Only when the writer is between that read and its wait, or another
     * thread holds the lock while the writer waits, does the nudge miss, and the writer looks at
     * its next poll. (An unpark would not do: a condition wait parks again until signalled or
     * timed out.)
     */
    private void nudge() {
        if (!holdsNone) {
            return;
        }
        nudged = true;
        if (lock.tryLock()) {
            try {
                work.signalAll();
            } finally {
                lock.unlock();
            }
        }
    }

    /** Releases the acknowledged messages (lock held). */
    private void acknowledged(Connection connection, long count) {
        int window = context.config().windowMessages();
        boolean windowWasFull = out.size() >= window;
        boolean lowWasFull = out.hasLowInFlight();
        out.acknowledge(count);
        if (out.isEmpty()) {
            connection.output().allDataAcknowledged();
        }
        if (!outbox.isEmpty() && (windowWasFull && out.size() < window || lowWasFull)) {
            work.signal(); // the writer waited for room in the window, or for LOW room
        }
    }

    /** The peer refused message {@code seq}; returns it (to report), or null if it is not kept. */
    Outgoing onReject(Connection connection, long seq) {
        lock.lock();
        try {
            if (active != connection) {
                return null;
            }
            InFlight refused = out.remove(seq);
            return refused == null ? null : refused.outgoing();
        } finally {
            lock.unlock();
        }
    }

    /** Messages handed to this node's kernel from the peer's stream: the acknowledgement to send. */
    long inboundCount() {
        return inbound.count();
    }

    /**
     * Hands a message frame over in its place in the inbound stream (see {@link
     * InboundStream#deliver}), if {@code connection} is still this lane's.
     *
     * @return false for a duplicate (dropped) or a frame of a replaced connection
     */
    boolean deliverInOrder(Connection connection, long seq, InboundStream.Delivery delivery) throws ProtocolException {
        synchronized (inbound) {
            return active == connection && inbound.deliver(seq, delivery);
        }
    }

    // ---------------------------------------------------------------- housekeeping

    /** Since when no connection carries this lane (meaningful while {@link #active()} is null). */
    long downSinceNs() {
        return life.downSinceNs();
    }

    /**
     * The peer has been down longer than the grace period (its {@link Peer} decides): stop accepting
     * messages for it and retire this link (the messenger forgets the peer; a later connection
     * starts afresh), and return what waited, to report to the senders. Null if it is connected
     * again or already retired.
     */
    List<Outgoing> expire() {
        lock.lock();
        try {
            return active != null || !life.retire() ? null : abandonAll();
        } finally {
            lock.unlock();
        }
    }

    /**
     * This lane alone has been down longer than the grace period while another lane of the peer is
     * up: its messages are given up (returned, for the caller to report) and new ones refused until
     * it connects again, so its senders hear of it and lane 1's NONE messages stop waiting for it.
     * Null if it is not newly so.
     */
    List<Outgoing> expireAlone(long nowNs) {
        lock.lock();
        try {
            if (active != null || !life.expireAlone(nowNs, outbox.isEmpty() && out.isEmpty())) {
                return null;
            }
            List<Outgoing> lost = abandonAll();
            return lost.isEmpty() ? null : lost;
        } finally {
            lock.unlock();
        }
    }

    /** The messenger closes: refuse new messages and return what waited. */
    List<Outgoing> close() {
        lock.lock();
        try {
            life.close();
            work.signalAll();
            return abandonAll();
        } finally {
            lock.unlock();
        }
    }

    private List<Outgoing> abandonAll() {
        var lost = new ArrayList<Outgoing>(out.size() + outbox.size());
        for (InFlight entry : out.reset()) {
            lost.add(entry.outgoing());
        }
        lost.addAll(outbox.abandon());
        return lost;
    }

    /** Waiting messages, and written ones not yet acknowledged. */
    int[] backlog() {
        lock.lock();
        try {
            return new int[] {outbox.size(), out.size()};
        } finally {
            lock.unlock();
        }
    }
}
