package io.etherware.services.network.internal;

import io.etherware.core.message.Criticality;
import io.etherware.core.message.Message;
import io.etherware.core.message.MessageFormatException;
import io.etherware.services.network.CloseReason;
import java.io.IOException;
import java.util.ArrayList;
import java.util.List;
import java.util.concurrent.TimeUnit;
import java.util.concurrent.locks.Condition;
import java.util.concurrent.locks.ReentrantLock;

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
 * <p>Locking: {@link #lock} guards the outbound state and the connections' writer requests;
 * the {@link #inbound} stream's monitor guards it and is taken first when both are needed. Nothing
 * calls the kernel while holding {@link #lock}.
 */
final class Link {

    /** How often a writer looks again at a NONE message held for lane 0 (see {@link Generations}). */
    private static final long BARRIER_POLL_NS = TimeUnit.MILLISECONDS.toNanos(1);

    final String nodeId;
    /** Which lane of the peer this is. */
    final int lane;
    final ReentrantLock lock = new ReentrantLock();
    /** Signalled when a writer may have work: messages, acknowledgements, control requests. */
    final Condition work = lock.newCondition();
    /** The peer's stream to this node on this lane. */
    private final InboundStream inbound = new InboundStream();

    private final NetworkContext context;
    /** Lane 0's link, whose earlier messages a NONE message of this lane waits for; null on lane 0. */
    private final Link precedent;
    /** This lane's unsettled messages by generation (guarded by lock). */
    private final Generations generations = new Generations();
    /** The latest generation a NONE message of lane 1 waits for, until settled; -1: none (guarded by lock). */
    private long syncUpTo = -1;
    /** Lane 1's link, nudged when an acknowledgement here may let its held NONE message go; set once. */
    volatile Link follower;
    /** This lane's writer waits with a NONE message held for lane 0 at the head of its queue. */
    private volatile boolean holdsNone;

    // Guarded by lock.
    private final OutboundQueue queue;
    /** This node's stream to the peer on this lane. */
    private final OutboundStream out;
    /** Someone (the writer thread, or a sender writing directly) owns the active connection's output. */
    private volatile boolean writerBusy;
    /** The writer has work but waits for a direct write to give the output back. */
    private boolean writerWaitsForToken;
    /** The queue's size, readable without the lock as a hint. */
    private volatile int queuedHint;
    private volatile Connection active;
    private volatile long downSinceNs;
    private boolean expired;
    /** Expired and removed from the messenger's peers: a later connection gets a new Peer. */
    private boolean retired;
    private boolean closed;


    Link(String nodeId, int lane, NetworkContext context, Link precedent) {
        this.nodeId = nodeId;
        this.lane = lane;
        this.context = context;
        this.precedent = precedent;
        this.out = new OutboundStream(context.lanes().size() == 1, generations);
        this.queue = new OutboundQueue(context.config().queueCapacity());
        this.downSinceNs = NetworkContext.nowNs();
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
        // A message that came from the network is relayed: one more hop than it had made.
        int hops = message.origin() == null ? 0 : message.origin().hops() + 1;
        if (hops > context.config().maxHops()) {
            throw new IllegalStateException("message " + message.messageId() + " was already relayed " + (hops - 1)
                    + " times (maxHops=" + context.config().maxHops() + "): the nodes' routes disagree");
        }
        Connection direct = active;
        // Encoded here, on the sender's thread: its size counts against the peer's byte bound.
        byte[] xml = encode(message, direct);
        OutboundQueue.Outcome outcome = null;
        InFlight written = null;
        lock.lock();
        try {
            if (closed) {
                throw new IllegalStateException("the network messenger of node '" + context.nodeId() + "' is closed");
            }
            if (expired) {
                throw new IllegalStateException("node '" + nodeId + "' is unreachable: disconnected for more than "
                        + TimeUnit.NANOSECONDS.toMillis(context.config().peerDownGraceNs()) + " ms");
            }
            long maxBytes = context.config().maxQueuedBytesPerPeer();
            var outgoing = new Outgoing(message, hops, xml, after, generations.take());
            if (direct != null && active == direct && !writerBusy && queue.isEmpty()
                    && !direct.requests.mustPrecedeMessages() && out.size() < context.config().windowMessages()
                    && out.bytes() + xml.length <= maxBytes && out.lowRoomFor(outgoing, 0) && mayGo(outgoing)
                    && direct.output().fitsDirectWrite(xml.length + Frame.DATA_OVERHEAD_BYTES)) {
                writerBusy = true;
                written = out.add(outgoing);
            } else {
                outcome = queue.offer(outgoing, maxBytes - out.bytes());
                queuedHint = queue.size();
                switch (outcome) {
                    case OutboundQueue.Outcome.Evicted evicted -> evicted.evicted().forEach(this::settle);
                    case OutboundQueue.Outcome.Full full -> settle(outgoing);
                    default -> { }
                }
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
        switch (outcome) {
            case OutboundQueue.Outcome.Evicted evicted -> {
                for (Outgoing each : evicted.evicted()) {
                    context.losses().dropped(each.message(), nodeId, "evicted by a more critical message from the full queue"
                            + " to node '" + nodeId + "'");
                }
            }
            case OutboundQueue.Outcome.Full full -> {
                String why = "the queue to node '" + nodeId + "' is full (queueCapacity="
                        + context.config().queueCapacity() + " messages, maxQueuedBytesPerPeer="
                        + context.config().maxQueuedBytesPerPeer() + " bytes with those in flight) of messages at"
                        + " least as critical as this one";
                if (message.qos().criticality().compareTo(Criticality.LOW) <= 0) {
                    context.losses().dropped(message, nodeId, why);
                } else {
                    throw new IllegalStateException(why);
                }
            }
            default -> { }
        }
    }

    /**
     * The message's XML, within the frame limit of {@code connection}'s peer (or this node's own
     * limit when none is connected), or an exception the kernel reports to the sender.
     */
    private byte[] encode(Message message, Connection connection) {
        byte[] xml;
        try {
            xml = context.codec().encode(message);
        } catch (MessageFormatException e) {
            throw new IllegalStateException("message " + message.messageId() + " does not encode: " + e.getMessage(), e);
        }
        int limit = connection != null ? connection.output().peerMaxFrameBytes() : context.config().maxFrameBytes();
        if (xml.length + Frame.DATA_OVERHEAD_BYTES > limit) {
            throw new IllegalStateException("message " + message.messageId() + " is a frame of "
                    + (xml.length + Frame.DATA_OVERHEAD_BYTES) + " bytes, over the " + limit
                    + " bytes node '" + nodeId + "' accepts");
        }
        return xml;
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
        lock.lock();
        try {
            writerBusy = false;
            if (writerWaitsForToken) {
                // Only then: waking an idle writer after every direct write would cost a thread
                // switch per message.
                writerWaitsForToken = false;
                work.signalAll();
            }
        } finally {
            lock.unlock();
        }
    }

    private void awaitToken() throws InterruptedException {
        writerWaitsForToken = true;
        work.await();
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

    /** The outcome of {@link #activate}. */
    /**
     * @param refusal why the connection is refused for a protocol error, or null (a duplicate, or
     *                the messenger closes)
     */
    record Activation(boolean accepted, Connection loser, List<InFlight> lost, String refusal) {
    }

    /**
     * Makes {@code candidate}, handshaken, this peer's connection, unless a connection that wins
     * the one-connection rule is already in use. Resumes or restarts both streams.
     *
     * A peer claiming more of our stream than was sent is refused, and our stream starts afresh.
     */
    Activation activate(Connection candidate, Frame.Resume theirs, java.util.function.Supplier<byte[]> announceBody) {
        synchronized (inbound) {
            lock.lock();
            try {
                if (closed || retired) {
                    return new Activation(false, candidate, List.of(), null);
                }
                Connection current = active;
                Connection loser = null;
                if (current != null && current != candidate) {
                    if (!candidate.isPreferredOver(current)) {
                        return new Activation(false, candidate, List.of(), null);
                    }
                    loser = current;
                }
                List<InFlight> lost = List.of();
                if (theirs.knownStreamId() == out.streamId()) {
                    // A RESUME that contradicts the stream: a restart raced a second connection, or
                    // a connection in the peer's name acknowledged what it now denies (an impostor,
                    // or a bug).
                    String refusal = out.resumeRefusal(theirs.receivedCount());
                    if (refusal != null) {
                        // With a connection in use, the candidate is the one that lies (an
                        // impostor, on a plain link): refuse it and leave the stream alone.
                        // Without one, start the stream afresh so the next connection agrees.
                        List<InFlight> unknown = current != null && current != candidate ? List.of() : out.reset();
                        return new Activation(false, candidate, unknown, refusal);
                    }
                    out.acknowledge(theirs.receivedCount());
                    candidate.requests.resend(out.unacknowledged());
                } else {
                    // The peer does not know our stream: what it did not acknowledge is of unknown
                    // fate; the peer starts our stream from 0 (it adopts its id from our RESUME).
                    lost = out.restartNumbering();
                    candidate.requests.resend(List.of());
                }
                inbound.resume(theirs.streamId());
                if (loser != null) {
                    loser.requests.requestBye(CloseReason.DUPLICATE, "replaced by the connection dialed by '"
                            + candidate.initiatorId() + "'");
                }
                active = candidate;
                expired = false;
                out.restartClock();
                // Read under the lock: an announcement published meanwhile finds this connection active.
                candidate.requests.announce(announceBody.get());
                work.signalAll();
                return new Activation(true, loser, lost, null);
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
            downSinceNs = NetworkContext.nowNs();
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
                    if (writerBusy) {
                        awaitToken();
                        continue;
                    }
                    WriterTurn last = connection.requests.takeBye();
                    writerBusy = last != null;
                    return last;
                }
                Outgoing head = queue.peek();
                boolean held = head != null && !mayGo(head);
                holdsNone = held;
                boolean sendable = head != null && out.size() < window && out.lowRoomFor(head, 0) && !held;
                if (!connection.requests.hasRequests() && !sendable) {
                    long waitNs = connection.output().heartbeatDueNs() - NetworkContext.nowNs();
                    if (waitNs > 0) {
                        // A NONE message held for lane 0 is looked at again every millisecond:
                        // lane 0 never signals this lane, so its threads never take this lock.
                        work.awaitNanos(held ? Math.min(waitNs, BARRIER_POLL_NS) : waitNs);
                        continue;
                    }
                    connection.requests.requestHeartbeat();
                }
                if (writerBusy) {
                    awaitToken(); // a sender is writing directly; it signals when done
                    continue;
                }
                break;
            }
            WriterTurn turn = connection.requests.takeRequests(batch);
            // New messages only once every message to send again is out: the peer expects the
            // stream in order.
            int room = connection.requests.mustPrecedeMessages() ? 0 : Math.min(batch, window - out.size());
            long lowChosen = 0;
            while (turn.fresh.size() < room) {
                Outgoing next = queue.peek();
                if (next == null || !out.lowRoomFor(next, lowChosen) || !mayGo(next)) {
                    break; // the rest are NONE or LOW too: they wait for acknowledgements
                }
                if (next.isSheddable()) {
                    lowChosen += next.xml().length;
                }
                turn.fresh.add(queue.poll());
            }
            queuedHint = queue.size();
            if (syncUpTo >= 0) {
                if (generations.settledUpTo(syncUpTo)) {
                    syncUpTo = -1;
                } else if (!turn.fresh.isEmpty() || !turn.resend.isEmpty()) {
                    turn.sync = true; // more of what the NONE message waits for goes out now
                }
            }
            writerBusy = true;
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
            givenUp.forEach(this::settle);
            if (active != connection) {
                queue.pushBack(encoded);
                queuedHint = queue.size();
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
            long closed = generations.close();
            if (!generations.settledUpTo(closed)) {
                // Its messages are settled when the peer acknowledges them, which it may put off
                // for up to 10 ms: a SYNC after them asks it to at once.
                syncUpTo = closed;
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

    /** Whether every message of {@code generation} and before is settled here. Lock-free. */
    boolean hasSettled(long generation) {
        return generations.settledUpTo(generation);
    }

    /** Whether a NONE message waiting for lane 0 may go (lock held). */
    private boolean mayGo(Outgoing next) {
        return next.after() < 0 || precedent == null || precedent.hasSettled(next.after());
    }

    /** {@code outgoing} leaves this lane for good without having been written (lock held). */
    private void settle(Outgoing outgoing) {
        generations.settle(outgoing.generation());
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
     * now rather than at its next 1 ms poll. Takes no lock (an unpark: the writer's wait loop
     * takes an early return as a reason to look again).
     */
    private void nudge() {
        Connection connection = active;
        Thread writer = connection == null ? null : connection.writerThread();
        if (holdsNone && writer != null) {
            java.util.concurrent.locks.LockSupport.unpark(writer);
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
        if (!queue.isEmpty() && (windowWasFull && out.size() < window || lowWasFull)) {
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
        return downSinceNs;
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
            if (active != null || retired || closed) {
                return null;
            }
            expired = true; // perhaps already, alone: what was put back since is given up now
            retired = true;
            return abandonAll();
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
            if (active != null || closed || nowNs - downSinceNs < context.config().peerDownGraceNs()
                    || expired && queue.isEmpty() && out.isEmpty()) {
                return null; // (messages a replaced writer put back after it expired are given up too)
            }
            expired = true;
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
            closed = true;
            work.signalAll();
            return abandonAll();
        } finally {
            lock.unlock();
        }
    }

    private List<Outgoing> abandonAll() {
        var lost = new ArrayList<Outgoing>(out.size() + queue.size());
        for (InFlight entry : out.reset()) {
            lost.add(entry.outgoing());
        }
        List<Outgoing> waited = queue.drain();
        waited.forEach(this::settle);
        lost.addAll(waited);
        queuedHint = 0;
        return lost;
    }

    /** Waiting messages, and written ones not yet acknowledged. */
    int[] backlog() {
        lock.lock();
        try {
            return new int[] {queue.size(), out.size()};
        } finally {
            lock.unlock();
        }
    }
}
