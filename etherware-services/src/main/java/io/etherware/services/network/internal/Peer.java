package io.etherware.services.network.internal;

import io.etherware.core.message.Criticality;
import io.etherware.core.message.Message;
import io.etherware.core.message.MessageFormatException;
import io.etherware.services.network.CloseReason;
import java.util.ArrayDeque;
import java.io.IOException;
import java.util.ArrayList;
import java.util.List;
import java.util.concurrent.TimeUnit;
import java.util.concurrent.locks.Condition;
import java.util.concurrent.locks.ReentrantLock;

/**
 * Everything this node keeps about one other node, across connections: the messages waiting
 * for it (by criticality), the messages written but not yet acknowledged, where both streams
 * stand, and which connection is the one in use.
 *
 * <p>Streams. Messages to a peer are numbered in a stream with a random id; the peer
 * acknowledges how many of them its kernel has. A new connection to the same peer resumes the
 * stream: what the peer already has is released, the rest is written again and duplicates are
 * dropped by number, so nothing is lost or delivered twice while both nodes live. If the peer
 * does not know the stream (it restarted), the unacknowledged messages are reported to their
 * senders as undeliverable and numbering starts over.
 *
 * <p>Locking: {@link #lock} guards the outbound state and the connections' writer requests;
 * {@link #inboundLock} guards the inbound stream and is taken first when both are needed. Nothing
 * calls the kernel while holding {@link #lock}.
 */
final class Peer {

    /**
     * Bytes of NONE and LOW messages written to the peer and not yet acknowledged, at most (one
     * larger message may go alone): a HIGH message then waits behind at most this much LOW data in
     * the sockets and the peer's reader, instead of behind whatever the socket buffers hold (MiBs
     * on loopback). The peer acknowledges every 64 KiB it receives, so LOW throughput is kept.
     */
    static final int LOW_IN_FLIGHT_BYTES = 128 * 1024;

    final String nodeId;
    final ReentrantLock lock = new ReentrantLock();
    /** Signalled when a writer may have work: messages, acknowledgements, control requests. */
    final Condition work = lock.newCondition();
    final Object inboundLock = new Object();

    private final Engine engine;

    // Guarded by lock.
    private final OutboundQueue queue;
    private final ArrayDeque<InFlight> inFlight = new ArrayDeque<>();
    private long streamId;
    private long nextSeq;
    /** Someone (the writer thread, or a sender writing directly) owns the active connection's output. */
    private volatile boolean writerBusy;
    /** The writer has work but waits for a direct write to give the output back. */
    private boolean writerWaitsForToken;
    /** The queue's size, readable without the lock as a hint. */
    private volatile int queuedHint;
    /** Bytes of the messages in flight. */
    private long inFlightBytes;
    /** Bytes of the NONE and LOW messages in flight. */
    private long lowInFlightBytes;
    private volatile long ackedCount;
    /** Since when something written is unacknowledged with no acknowledgement progress; 0: nothing. */
    private volatile long unackedSinceNs;
    private volatile Connection active;
    private long remoteIncarnation;
    private long downSinceNs;
    private boolean expired;
    /** Expired and removed from the messenger's peers: a later connection gets a new Peer. */
    private boolean retired;
    private boolean closed;

    // Guarded by inboundLock; inboundNext is read without it by writers (piggybacked acks).
    private long inboundStreamId;
    private volatile long inboundNext;

    Peer(String nodeId, Engine engine) {
        this.nodeId = nodeId;
        this.engine = engine;
        this.queue = new OutboundQueue(engine.config().queueCapacity());
        this.streamId = engine.newStreamId();
        this.downSinceNs = engine.nowNs();
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
    void enqueue(Message message) {
        // A message that came from the network is relayed: one more hop than it had made.
        int hops = message.origin() == null ? 0 : message.origin().hops() + 1;
        if (hops > engine.config().maxHops()) {
            throw new IllegalStateException("message " + message.messageId() + " was already relayed " + (hops - 1)
                    + " times (maxHops=" + engine.config().maxHops() + "): the nodes' routes disagree");
        }
        Connection direct = active;
        // Encoded here, on the sender's thread: its size counts against the peer's byte bound.
        byte[] xml = encode(message, direct);
        var outgoing = new Outgoing(message, hops, xml);
        OutboundQueue.Outcome outcome = null;
        InFlight written = null;
        lock.lock();
        try {
            if (closed) {
                throw new IllegalStateException("the network messenger of node '" + engine.nodeId() + "' is closed");
            }
            if (expired) {
                throw new IllegalStateException("node '" + nodeId + "' is unreachable: disconnected for more than "
                        + TimeUnit.NANOSECONDS.toMillis(engine.config().peerDownGraceNs()) + " ms");
            }
            long maxBytes = engine.config().maxQueuedBytesPerPeer();
            if (direct != null && active == direct && !writerBusy && queue.isEmpty()
                    && !direct.requests.mustPrecedeMessages() && inFlight.size() < engine.config().windowMessages()
                    && inFlightBytes + xml.length <= maxBytes && lowRoomFor(outgoing, 0)
                    && direct.fitsDirectWrite(xml.length + Frame.DATA_OVERHEAD_BYTES)) {
                writerBusy = true;
                written = new InFlight(nextSeq++, outgoing, xml);
                markUnacked();
                addInFlight(written);
            } else {
                outcome = queue.offer(outgoing, maxBytes - inFlightBytes);
                queuedHint = queue.size();
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
                    engine.dropped(each.message(), nodeId, "evicted by a more critical message from the full queue"
                            + " to node '" + nodeId + "'");
                }
            }
            case OutboundQueue.Outcome.Full full -> {
                String why = "the queue to node '" + nodeId + "' is full (queueCapacity="
                        + engine.config().queueCapacity() + " messages, maxQueuedBytesPerPeer="
                        + engine.config().maxQueuedBytesPerPeer() + " bytes with those in flight) of messages at"
                        + " least as critical as this one";
                if (message.qos().criticality().compareTo(Criticality.LOW) <= 0) {
                    engine.dropped(message, nodeId, why);
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
            xml = engine.codec().encode(message);
        } catch (MessageFormatException e) {
            throw new IllegalStateException("message " + message.messageId() + " does not encode: " + e.getMessage(), e);
        }
        int limit = connection != null ? connection.peerMaxFrameBytes() : engine.config().maxFrameBytes();
        if (xml.length + Frame.DATA_OVERHEAD_BYTES > limit) {
            throw new IllegalStateException("message " + message.messageId() + " is a frame of "
                    + (xml.length + Frame.DATA_OVERHEAD_BYTES) + " bytes, over the " + limit
                    + " bytes node '" + nodeId + "' accepts");
        }
        return xml;
    }

    private void writeDirect(Connection connection, InFlight entry) {
        try {
            connection.writeDirect(entry);
        } catch (IOException e) {
            // Kept in flight: the next connection sends it again, or its sender hears it is lost.
            engine.closeLater(connection, CloseReason.IO_ERROR, "writing to node '" + nodeId + "' failed: " + e);
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
        synchronized (inboundLock) {
            lock.lock();
            try {
                return new Frame.Resume(streamId, inboundStreamId, inboundNext);
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
    record Activation(boolean accepted, Connection loser, List<InFlight> lost, boolean restarted, String refusal) {
    }

    /**
     * Makes {@code candidate}, handshaken, this peer's connection, unless a connection that wins
     * the one-connection rule is already in use. Resumes or restarts both streams.
     *
     * A peer claiming more of our stream than was sent is refused, and our stream starts afresh.
     */
    Activation activate(Connection candidate, Frame.Hello hello, Frame.Resume theirs) {
        synchronized (inboundLock) {
            lock.lock();
            try {
                if (closed || retired) {
                    return new Activation(false, candidate, List.of(), false, null);
                }
                Connection current = active;
                Connection loser = null;
                if (current != null && current != candidate) {
                    if (!candidate.isPreferredOver(current)) {
                        return new Activation(false, candidate, List.of(), false, null);
                    }
                    loser = current;
                }
                boolean restarted = remoteIncarnation != 0 && remoteIncarnation != hello.incarnation();
                remoteIncarnation = hello.incarnation();
                List<InFlight> lost = List.of();
                if (theirs.knownStreamId() == streamId) {
                    String refusal = null;
                    if (theirs.receivedCount() > nextSeq) {
                        // The streams disagree (a restart raced a second connection): start ours
                        // afresh under a new id, which the peer adopts on the next connection.
                        refusal = "the peer claims " + theirs.receivedCount() + " messages of stream "
                                + Long.toHexString(streamId) + ", only " + nextSeq + " were sent";
                    } else if (theirs.receivedCount() < ackedCount) {
                        // Fewer than it acknowledged before: those are released and cannot be sent
                        // again, so resuming would leave a gap the peer never gets past (a
                        // connection in its name acknowledged them: an impersonator, or a bug).
                        refusal = "the peer claims " + theirs.receivedCount() + " messages of stream "
                                + Long.toHexString(streamId) + ", but had acknowledged " + ackedCount;
                    }
                    if (refusal != null) {
                        // With a connection in use, the candidate is the one that lies (an
                        // impostor, on a plain link): refuse it and leave the stream alone.
                        // Without one, start the stream afresh so the next connection agrees.
                        List<InFlight> unknown = current != null && current != candidate ? List.of() : resetStream();
                        return new Activation(false, candidate, unknown, false, refusal);
                    }
                    releaseInFlightBelow(theirs.receivedCount());
                    ackedCount = Math.max(ackedCount, theirs.receivedCount());
                    candidate.requests.resend(List.copyOf(inFlight));
                } else {
                    // The peer does not know our stream: what it did not acknowledge is of unknown
                    // fate; the peer starts our stream from 0 (it adopts its id from our RESUME).
                    lost = List.copyOf(inFlight);
                    inFlight.clear();
                    inFlightBytes = 0;
                    lowInFlightBytes = 0;
                    unackedSinceNs = 0;
                    nextSeq = 0;
                    ackedCount = 0;
                    candidate.requests.resend(List.of());
                }
                if (theirs.streamId() != inboundStreamId) {
                    inboundStreamId = theirs.streamId();
                    inboundNext = 0;
                }
                if (loser != null) {
                    loser.requests.requestBye(CloseReason.DUPLICATE, "replaced by the connection dialed by '"
                            + candidate.initiatorId() + "'");
                }
                active = candidate;
                expired = false;
                unackedSinceNs = inFlight.isEmpty() ? 0 : engine.nowNs();
                candidate.requests.announce(engine.announceBody());
                work.signalAll();
                return new Activation(true, loser, lost, restarted, null);
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
            downSinceNs = engine.nowNs();
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
        int window = engine.config().windowMessages();
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
                boolean sendable = head != null && inFlight.size() < window && lowRoomFor(head, 0);
                if (!connection.requests.hasRequests() && !sendable) {
                    long waitNs = connection.heartbeatDueNs() - engine.nowNs();
                    if (waitNs > 0) {
                        work.awaitNanos(waitNs);
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
            int room = connection.requests.mustPrecedeMessages() ? 0 : Math.min(batch, window - inFlight.size());
            long lowChosen = 0;
            while (turn.fresh.size() < room) {
                Outgoing next = queue.peek();
                if (next == null || !lowRoomFor(next, lowChosen)) {
                    break; // the rest are NONE or LOW too: they wait for acknowledgements
                }
                if (next.isSheddable()) {
                    lowChosen += next.xml().length;
                }
                turn.fresh.add(queue.poll());
            }
            queuedHint = queue.size();
            writerBusy = true;
            return turn;
        } finally {
            lock.unlock();
        }
    }

    /**
     * Numbers the encoded messages of a turn and keeps them until acknowledged; null if the
     * connection is no longer the peer's, in which case they go back to the front of the queue.
     */
    List<InFlight> assign(Connection connection, List<Outgoing> encoded, List<byte[]> xml) {
        lock.lock();
        try {
            if (active != connection) {
                queue.pushBack(encoded);
                queuedHint = queue.size();
                work.signalAll();
                return null;
            }
            var assigned = new ArrayList<InFlight>(encoded.size());
            if (!encoded.isEmpty()) {
                markUnacked();
            }
            for (int i = 0; i < encoded.size(); i++) {
                var entry = new InFlight(nextSeq++, encoded.get(i), xml.get(i));
                addInFlight(entry);
                assigned.add(entry);
            }
            return assigned;
        } finally {
            lock.unlock();
        }
    }

    private void releaseInFlightBelow(long count) {
        boolean released = false;
        while (!inFlight.isEmpty() && inFlight.peekFirst().seq() < count) {
            removedFromFlight(inFlight.pollFirst());
            released = true;
        }
        if (inFlight.isEmpty()) {
            unackedSinceNs = 0;
        } else if (released) {
            unackedSinceNs = engine.nowNs();
        }
    }

    /** Whether {@code next} may go now, with {@code chosen} more LOW bytes already taken (lock held). */
    private boolean lowRoomFor(Outgoing next, long chosen) {
        if (!next.isSheddable()) {
            return true;
        }
        long already = lowInFlightBytes + chosen;
        return already == 0 || already + next.xml().length <= LOW_IN_FLIGHT_BYTES;
    }

    private void addInFlight(InFlight entry) {
        inFlight.addLast(entry);
        inFlightBytes += entry.xml().length;
        if (entry.outgoing().isSheddable()) {
            lowInFlightBytes += entry.xml().length;
        }
    }

    private void removedFromFlight(InFlight entry) {
        inFlightBytes -= entry.xml().length;
        if (entry.outgoing().isSheddable()) {
            lowInFlightBytes -= entry.xml().length;
        }
    }

    /** Something is about to be in flight (lock held): the not-reading clock starts if it was empty. */
    private void markUnacked() {
        if (inFlight.isEmpty()) {
            unackedSinceNs = engine.nowNs();
        }
    }

    /**
     * How long the peer has read nothing of what was written to it: no acknowledgement progress
     * while messages are in flight, or a write of the active connection blocked.
     */
    long unreadForNs(long nowNs) {
        Connection connection = active;
        long since = unackedSinceNs;
        long unacked = since == 0 ? 0 : nowNs - since;
        return Math.max(unacked, connection == null ? 0 : connection.writeBlockedForNs(nowNs));
    }

    /** The peer's kernel has the first {@code count} messages of the stream. */
    void onAck(Connection connection, long count) throws ProtocolException {
        if (count == ackedCount) {
            return;
        }
        List<InFlight> lost;
        String error;
        lock.lock();
        try {
            if (active != connection || count == ackedCount) {
                return;
            }
            if (count > nextSeq) {
                error = "acknowledgement of " + count + " messages, only " + nextSeq + " were sent";
                lost = resetStream();
            } else if (count < ackedCount) {
                // Acknowledgements are cumulative: one that goes back contradicts what was released.
                error = "acknowledgement of " + count + " messages after " + ackedCount + " were acknowledged";
                lost = resetStream();
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
    }

    /** Releases the acknowledged messages (lock held). */
    private void acknowledged(Connection connection, long count) {
        int window = engine.config().windowMessages();
        boolean windowWasFull = inFlight.size() >= window;
        boolean lowWasFull = lowInFlightBytes > 0;
        releaseInFlightBelow(count);
        ackedCount = count;
        if (inFlight.isEmpty()) {
            connection.allDataAcknowledged();
        }
        if (!queue.isEmpty() && (windowWasFull && inFlight.size() < window || lowWasFull)) {
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
            var each = inFlight.iterator();
            while (each.hasNext()) {
                InFlight entry = each.next();
                if (entry.seq() == seq) {
                    each.remove();
                    removedFromFlight(entry);
                    return entry.outgoing();
                }
            }
            return null;
        } finally {
            lock.unlock();
        }
    }

    /** Messages handed to this node's kernel from the peer's stream: the acknowledgement to send. */
    long inboundCount() {
        return inboundNext;
    }

    /**
     * Checks a message frame's place in the inbound stream; on success runs {@code delivery}
     * and counts it, all under the inbound lock so that two connections (during a replacement)
     * never deliver out of order or twice.
     *
     * @return false for a duplicate (dropped) or a frame of a replaced connection
     */
    boolean deliverInOrder(Connection connection, long seq, InboundDelivery delivery) throws ProtocolException {
        synchronized (inboundLock) {
            if (active != connection) {
                return false;
            }
            if (seq < inboundNext) {
                return false;
            }
            if (seq > inboundNext) {
                throw new ProtocolException(CloseReason.SEQUENCE_ERROR, "message frame " + seq + " where "
                        + inboundNext + " was expected");
            }
            try {
                delivery.deliver();
            } finally {
                inboundNext = seq + 1; // delivered, or refused for good: never asked for again
            }
            return true;
        }
    }

    /** The hand-over of one inbound message to the kernel. */
    @FunctionalInterface
    interface InboundDelivery {
        void deliver() throws ProtocolException;
    }

    // ---------------------------------------------------------------- housekeeping

    /**
     * If the peer has been down longer than the grace period: stop accepting messages for it and
     * retire it (the messenger forgets it; a later connection starts afresh), and return what
     * waited, to report to the senders. Null if it is not newly expired.
     */
    List<Outgoing> expireIfDown(long nowNs) {
        lock.lock();
        try {
            if (active != null || expired || closed || nowNs - downSinceNs < engine.config().peerDownGraceNs()) {
                return null;
            }
            expired = true;
            retired = true;
            return abandonAll();
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
        var lost = new ArrayList<Outgoing>(inFlight.size() + queue.size());
        for (InFlight entry : resetStream()) {
            lost.add(entry.outgoing());
        }
        lost.addAll(queue.drain());
        queuedHint = 0;
        return lost;
    }

    /**
     * Starts the outbound stream afresh under a new id (the peer, when it sees the id, must not
     * expect the old numbers) and returns the unacknowledged messages, whose fate is unknown.
     */
    private List<InFlight> resetStream() {
        List<InFlight> lost = List.copyOf(inFlight);
        inFlight.clear();
        inFlightBytes = 0;
        lowInFlightBytes = 0;
        unackedSinceNs = 0;
        streamId = engine.newStreamId();
        nextSeq = 0;
        ackedCount = 0;
        return lost;
    }


    /** Waiting messages, and written ones not yet acknowledged. */
    int[] backlog() {
        lock.lock();
        try {
            return new int[] {queue.size(), inFlight.size()};
        } finally {
            lock.unlock();
        }
    }

    /** The stream with the peer contradicted itself and was started afresh; {@link #lost} are of unknown fate. */
    static final class StreamResetException extends ProtocolException {
        final transient List<InFlight> lost;

        StreamResetException(String message, List<InFlight> lost) {
            super(CloseReason.SEQUENCE_ERROR, message);
            this.lost = lost;
        }
    }
}
