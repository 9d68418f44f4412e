package io.etherware.services.network.internal;

import io.etherware.core.message.Message;
import io.etherware.core.message.MessageFormatException;
import io.etherware.core.message.Origin;
import io.etherware.services.network.CloseReason;
import io.etherware.services.time.TimeSample;
import java.io.EOFException;
import java.io.IOException;
import java.io.InputStream;
import java.net.Socket;
import java.net.SocketTimeoutException;
import java.util.ArrayList;
import java.util.List;
import java.util.concurrent.TimeUnit;
import javax.net.ssl.SSLException;

/**
 * One TCP connection to another node: the handshake, then a reader (the thread that ran the
 * handshake) and a writer thread. The reader hands messages to the kernel in stream order and
 * answers control frames through the writer; the writer sends what the {@link Peer} has, most
 * critical first, and flushes once per turn, so a burst leaves in few system calls.
 *
 * <p>A dead or slow peer blocks only this connection's two threads; senders only ever queue.
 *
 * <p>Thread-safety: the writer requests are guarded by the peer's lock; {@link #close} may be
 * called from any thread, once takes effect.
 */
final class Connection implements Runnable {

    /** How long a closing connection waits for its writer to say BYE, and drains the input. */
    private static final long CLOSE_GRACE_MS = 500;
    /** Most messages a writer takes in one turn. */
    private static final int BATCH = 64;
    private static final int DIRECT_BUDGET_MAX_BYTES = 64 * 1024;
    /** A receiver acknowledges at least every this many bytes of messages. */
    static final int ACK_EVERY_BYTES = 64 * 1024;

    private final Engine engine;
    private final Socket socket;
    private final Dialer dialer;
    private final String remote;
    private volatile Peer peer;
    private Frame.Hello hello;
    /** The node id the connection authenticated (TLS), or null on a plain link. */
    private String authenticatedId;
    private FrameReader reader;
    private FrameWriter writer;
    private int peerMaxFrameBytes;
    /** Unacknowledged bytes below which a sender may write directly without ever blocking. */
    private int directBudgetBytes;
    private volatile Thread readerThread;
    private volatile Thread writerThread;
    private volatile boolean closing;
    private volatile boolean activated;
    /** Guarded by this: {@link #close} runs once. */
    private boolean closed;

    /** What the writer is asked to send besides messages; guarded by the peer's lock. */
    final WriterRequests requests = new WriterRequests();

    private volatile long lastWriteNs;
    /** When the writer thread's current write began, or 0. */
    private volatile long writingSinceNs;
    private volatile long lastAckSent;
    /** Bytes framed on this connection; written by whoever owns the output. */
    private volatile long bytesWritten;
    /** Where the last message frame written ends. */
    private volatile long lastDataEndOffset;
    /** Bytes the peer has certainly read: up to the last message frame, once all were acknowledged. */
    private volatile long readByPeerOffset;

    /** Reader thread only: message bytes received since the last acknowledgement was asked for. */
    private long bytesSinceAckRequest;

    // Control thread only.
    long nextProbeNs;
    int probesSent;

    /**
     * @param dialer the dialer that opened it, or null for an accepted connection
     */
    Connection(Engine engine, Socket socket, Dialer dialer) {
        this.engine = engine;
        this.socket = socket;
        this.dialer = dialer;
        this.remote = String.valueOf(socket.getRemoteSocketAddress());
        this.lastWriteNs = engine.nowNs();
        this.nextProbeNs = lastWriteNs;
    }

    // ---------------------------------------------------------------- the reader thread

    @Override
    public void run() {
        readerThread = Thread.currentThread();
        try {
            handshake();
        } catch (ProtocolException e) {
            engine.counters().handshakesFailed.increment();
            close(e.reason(), e.getMessage());
            return;
        } catch (SocketTimeoutException e) {
            engine.counters().handshakesFailed.increment();
            close(CloseReason.HANDSHAKE_TIMEOUT, "no handshake within "
                    + TimeUnit.NANOSECONDS.toMillis(engine.config().handshakeTimeoutNs()) + " ms");
            return;
        } catch (IOException e) {
            engine.counters().handshakesFailed.increment();
            close(closing ? CloseReason.SHUTDOWN : CloseReason.IO_ERROR, "handshake failed: " + e);
            return;
        } finally {
            engine.handshakeEnded(this);
        }
        if (!activated) {
            return;
        }
        Thread writing = new ConnectionThread(this::writeLoop, "etherware-net-" + engine.nodeId() + "-write-" + peer.nodeId);
        writerThread = writing;
        writing.start();
        readLoop();
    }

    private void handshake() throws IOException {
        socket.setTcpNoDelay(true);
        socket.setKeepAlive(true);
        socket.setSoTimeout((int) Math.max(1, TimeUnit.NANOSECONDS.toMillis(engine.config().handshakeTimeoutNs())));
        try {
            authenticatedId = engine.config().connectionFactory().authenticate(socket).orElse(null);
        } catch (SocketTimeoutException e) {
            throw e;
        } catch (SSLException e) {
            throw new ProtocolException(CloseReason.AUTHENTICATION_FAILED, "TLS handshake failed: " + e.getMessage(), e);
        }
        reader = new FrameReader(socket.getInputStream(), engine.config().maxFrameBytes());
        writer = new FrameWriter(socket.getOutputStream());
        writer.hello(new Frame.Hello(Frame.VERSION, engine.nodeId(), engine.incarnation(),
                engine.kernel().clock().epochNanos(), engine.config().maxFrameBytes()));
        writer.flush();
        hello = reader.readHello();
        long helloArrivedEpochNs = engine.kernel().clock().epochNanos();
        if (authenticatedId != null && !authenticatedId.equals(hello.nodeId())) {
            throw new ProtocolException(CloseReason.AUTHENTICATION_FAILED, "the peer's certificate names node '"
                    + authenticatedId + "' but its HELLO says '" + hello.nodeId() + "'");
        }
        if (hello.nodeId().equals(engine.nodeId())) {
            throw new ProtocolException(CloseReason.BAD_HANDSHAKE, "the peer has this node's id '" + hello.nodeId()
                    + "': node ids must be unique (or a node dialed itself)");
        }
        if (dialer != null) {
            dialer.identified(hello.nodeId());
        }
        peerMaxFrameBytes = Math.min(hello.maxFrameBytes(), engine.config().maxFrameBytes());
        // A quarter of the send buffer: the kernel counts its own overhead against the rest.
        directBudgetBytes = Math.min(DIRECT_BUDGET_MAX_BYTES, socket.getSendBufferSize() / 4);
        Peer known = engine.peer(hello.nodeId());
        peer = known;
        writer.resume(known.resumeState());
        writer.flush();
        Frame second = reader.next();
        if (!(second instanceof Frame.Resume theirs)) {
            throw new ProtocolException(CloseReason.BAD_HANDSHAKE, "expected RESUME after HELLO, got "
                    + second.getClass().getSimpleName());
        }
        bytesWritten = writer.bytes();
        Thread.currentThread().setName("etherware-net-" + engine.nodeId() + "-read-" + known.nodeId);
        engine.handshakeEnded(this); // no longer a pending handshake that a flood could push out
        activated = engine.activate(this, hello, theirs, helloArrivedEpochNs);
        socket.setSoTimeout((int) Math.max(1, TimeUnit.NANOSECONDS.toMillis(engine.config().heartbeatTimeoutNs())));
    }

    private void readLoop() {
        engine.configureIoThread();
        try {
            while (!closing) {
                switch (reader.next()) {
                    case Frame.Data data -> onData(data);
                    case Frame.Ack ack -> peer.onAck(this, ack.count());
                    case Frame.Heartbeat heartbeat -> { }
                    case Frame.Announce announced -> {
                        if (peer.active() == this) {
                            engine.routes().announce(peer, announced.profiles());
                            engine.signalStateChanged();
                        }
                    }
                    case Frame.TimeRequest request -> requestTimeReply(request.t1(), engine.kernel().clock().epochNanos());
                    case Frame.TimeReply reply -> engine.networkTime().onExchange(peer.nodeId,
                            new TimeSample(reply.t1(), reply.t2(), reply.t3(), engine.kernel().clock().epochNanos()));
                    case Frame.Reject rejected -> {
                        Outgoing refused = peer.onReject(this, rejected.seq());
                        if (refused != null) {
                            engine.lost(refused.message(), "node '" + peer.nodeId + "' refused it: " + rejected.reason());
                        }
                    }
                    case Frame.Bye goodbye -> {
                        if (CloseReason.ofCode(goodbye.code()) == CloseReason.SHUTDOWN && peer.active() == this) {
                            engine.peerShutDown(peer);
                        }
                        close(CloseReason.PEER_CLOSED, "node '" + peer.nodeId + "' closed the connection: "
                                + CloseReason.ofCode(goodbye.code()) + ": " + goodbye.text());
                        return;
                    }
                    case Frame.Hello unexpected -> throw new ProtocolException(CloseReason.MALFORMED_FRAME, "HELLO again");
                    case Frame.Resume unexpected -> throw new ProtocolException(CloseReason.MALFORMED_FRAME,
                            "RESUME after the handshake");
                }
            }
        } catch (RefusedMessageException e) {
            peer.lock.lock();
            try {
                requests.reject(new Frame.Reject(e.seq, e.getMessage()));
            } finally {
                peer.lock.unlock();
            }
            close(e.reason(), e.getMessage());
        } catch (ProtocolException e) {
            close(e.reason(), e.getMessage());
            if (e instanceof Peer.StreamResetException reset) {
                engine.reportLost(reset.lost, "the streams with node '" + peer.nodeId
                        + "' disagreed; its fate is unknown");
            }
        } catch (SocketTimeoutException e) {
            close(CloseReason.HEARTBEAT_TIMEOUT, "nothing from node '" + peer.nodeId + "' for "
                    + TimeUnit.NANOSECONDS.toMillis(engine.config().heartbeatTimeoutNs()) + " ms");
        } catch (EOFException e) {
            close(CloseReason.PEER_CLOSED, "node '" + peer.nodeId + "' closed the connection");
        } catch (IOException e) {
            close(closing ? CloseReason.SHUTDOWN : CloseReason.IO_ERROR, "reading from node '" + peer.nodeId
                    + "' failed: " + e);
        }
    }

    /**
     * A message frame refused for good (its XML does not decode, or it lies about its origin): its
     * sender hears of it by REJECT, and the connection closes.
     */
    private static final class RefusedMessageException extends ProtocolException {
        final long seq;

        RefusedMessageException(long seq, CloseReason reason, String text, Throwable cause) {
            super(reason, "message frame " + seq + " " + text, cause);
            this.seq = seq;
        }
    }

    private void onData(Frame.Data data) throws ProtocolException {
        peer.onAck(this, data.ack());
        awaitInboundRoom(data.xml().length);
        boolean delivered = peer.deliverInOrder(this, data.seq(), () -> {
            Message message;
            try {
                message = engine.codec().decode(data.xml());
            } catch (MessageFormatException e) {
                throw new RefusedMessageException(data.seq(), CloseReason.MALFORMED_MESSAGE, "does not decode: "
                        + e.getMessage(), e);
            }
            engine.deliverLocally(engine.networkTime().toLocal(peer.nodeId, message.withOrigin(originOf(data, message))));
        });
        if (!delivered) {
            if (peer.active() != this) {
                return; // replaced: the new connection carries the stream on, and closes this one
            }
            engine.counters().duplicates.increment();
        } else {
            bytesSinceAckRequest += data.xml().length;
            if (peer.inboundCount() - lastAckSent >= engine.config().windowMessages() / 4
                    || bytesSinceAckRequest >= ACK_EVERY_BYTES) {
                // By count for small messages, by bytes for large ones: a sender keeps at most
                // Peer.LOW_IN_FLIGHT_BYTES of LOW messages unacknowledged.
                bytesSinceAckRequest = 0;
                requestAck();
            }
        }
    }

    /**
     * Where a message came from, from this connection's node, never from the message alone: sent
     * directly (hops 0), its id must name this connection's node; relayed, the relay vouches for
     * the origin its id names (the rule is in {@link Origin}).
     */
    private Origin originOf(Frame.Data data, Message message) throws RefusedMessageException {
        String named = message.messageId().nodeId();
        if (data.hops() == 0) {
            if (!named.equals(peer.nodeId)) {
                throw new RefusedMessageException(data.seq(), CloseReason.ORIGIN_MISMATCH, "has id " + message.messageId()
                        + " of node '" + named + "' but was sent directly by node '" + peer.nodeId
                        + "': a node may only send messages under its own id", null);
            }
            return new Origin(peer.nodeId, peer.nodeId, 0, authenticatedId != null, data.xml().length);
        }
        return new Origin(named, peer.nodeId, data.hops(), authenticatedId != null, data.xml().length);
    }

    /**
     * Waits, not reading, while this peer's messages held in the kernel's queues and this one
     * would exceed {@link io.etherware.services.network.NetworkConfig#maxInboundBytesPerPeer}: the
     * peer's writes then back up over TCP, and a peer that floods a slow component is slowed down
     * instead of filling the heap. Polls every millisecond; ends when the connection closes.
     */
    private void awaitInboundRoom(int bytes) {
        long max = engine.config().maxInboundBytesPerPeer();
        if (engine.kernel().queuedBytesFrom(peer.nodeId) + bytes <= max) {
            return;
        }
        engine.counters().inboundPauses.increment();
        while (!closing && engine.kernel().queuedBytesFrom(peer.nodeId) + bytes > max) {
            java.util.concurrent.locks.LockSupport.parkNanos(1_000_000);
        }
    }

    // ---------------------------------------------------------------- the writer thread

    private void writeLoop() {
        engine.configureIoThread();
        try {
            while (true) {
                WriterTurn turn = peer.nextTurn(this, BATCH);
                if (turn == null) {
                    return;
                }
                try {
                    write(turn);
                    if (turn.isLast()) {
                        socket.shutdownOutput();
                        return;
                    }
                } finally {
                    peer.endTurn();
                }
            }
        } catch (IOException e) {
            if (!closing) {
                close(CloseReason.IO_ERROR, "writing to node '" + peer.nodeId + "' failed: " + e);
            }
        } catch (InterruptedException e) {
            Thread.currentThread().interrupt();
            close(CloseReason.SHUTDOWN, "writer interrupted");
        }
    }

    private void write(WriterTurn turn) throws IOException {
        writingSinceNs = engine.nowNs();
        try {
            writeTurn(turn);
        } finally {
            writingSinceNs = 0;
        }
    }

    /**
     * How long the current write has been blocked (0: none in progress): a peer that reads nothing
     * fills the socket's buffers, and the writer's next write never returns.
     */
    long writeBlockedForNs(long nowNs) {
        long since = writingSinceNs;
        return since == 0 ? 0 : nowNs - since;
    }

    private void writeTurn(WriterTurn turn) throws IOException {
        long ackNow = peer.inboundCount();
        boolean carriedAck = false;
        if (turn.reject != null) {
            writer.reject(turn.reject.seq(), turn.reject.reason());
        }
        if (turn.announce != null) {
            writer.announce(turn.announce);
        }
        for (InFlight again : turn.resend) {
            writer.data(again.seq(), ackNow, again.outgoing().hops(), again.xml());
            engine.counters().resent.increment();
            carriedAck = true;
        }
        if (carriedAck) {
            lastDataEndOffset = writer.bytes();
        }
        if (!turn.fresh.isEmpty()) {
            carriedAck |= writeFresh(turn.fresh, ackNow);
        }
        if (turn.ack && !carriedAck) {
            writer.ack(ackNow);
            carriedAck = true;
        }
        if (carriedAck) {
            lastAckSent = ackNow;
        }
        if (turn.heartbeat) {
            writer.heartbeat();
        }
        if (turn.probe || !turn.timeReplies.isEmpty()) {
            // Time frames go out alone, stamped just before they leave: queued bytes ahead of
            // them would count as path delay.
            writer.flush();
            for (long[] request : turn.timeReplies) {
                writer.timeReply(request[0], request[1], engine.kernel().clock().epochNanos());
                writer.flush();
            }
            if (turn.probe) {
                writer.timeRequest(engine.kernel().clock().epochNanos());
            }
        }
        if (turn.bye != null) {
            writer.bye(turn.bye.code(), turn.bye.text());
        }
        writer.flush();
        bytesWritten = writer.bytes();
        lastWriteNs = engine.nowNs();
    }

    /** Numbers and writes new messages (encoded by their senders); reports those that cannot go. */
    private boolean writeFresh(List<Outgoing> fresh, long ackNow) throws IOException {
        var encoded = new ArrayList<Outgoing>(fresh.size());
        var xml = new ArrayList<byte[]>(fresh.size());
        for (Outgoing outgoing : fresh) {
            int frameBytes = outgoing.xml().length + Frame.DATA_OVERHEAD_BYTES;
            if (frameBytes <= peerMaxFrameBytes) {
                encoded.add(outgoing);
                xml.add(outgoing.xml());
            } else {
                // Queued before this peer said its limit, which is below this node's own.
                engine.lost(outgoing.message(), "its frame of " + frameBytes + " bytes is over the "
                        + peerMaxFrameBytes + " bytes node '" + peer.nodeId + "' accepts");
            }
        }
        List<InFlight> assigned = peer.assign(this, encoded, xml);
        if (assigned == null) {
            return false;
        }
        for (InFlight entry : assigned) {
            writer.data(entry.seq(), ackNow, entry.outgoing().hops(), entry.xml());
        }
        lastDataEndOffset = writer.bytes();
        engine.counters().sent.add(assigned.size());
        return !assigned.isEmpty();
    }

    /**
     * Writes one message frame on the calling thread, which owns the output meanwhile (see
     * {@link Peer#enqueue}).
     */
    void writeDirect(InFlight entry) throws IOException {
        long ackNow = peer.inboundCount();
        writer.data(entry.seq(), ackNow, entry.outgoing().hops(), entry.xml());
        writer.flush();
        lastDataEndOffset = writer.bytes();
        bytesWritten = lastDataEndOffset;
        lastAckSent = ackNow;
        lastWriteNs = engine.nowNs();
        engine.counters().sent.increment();
    }

    int peerMaxFrameBytes() {
        return peerMaxFrameBytes;
    }

    /**
     * Whether a sender may write {@code frameBytes} more directly: the bytes the peer may not have
     * read yet (everything after the last message frame it acknowledged, control frames included)
     * plus these stay within a quarter of the socket's send buffer, so the write cannot block
     * even on a peer that stopped reading.
     */
    boolean fitsDirectWrite(int frameBytes) {
        return bytesWritten - readByPeerOffset + frameBytes <= directBudgetBytes;
    }

    /**
     * Every message frame written so far is acknowledged (peer's lock held): the peer has read
     * the stream up to the last of them. A frame still being written ends later, so this errs
     * on the safe side.
     */
    void allDataAcknowledged() {
        readByPeerOffset = Math.max(readByPeerOffset, lastDataEndOffset);
    }

    // ---------------------------------------------------------------- writer requests (under peer.lock)

    long heartbeatDueNs() {
        return lastWriteNs + engine.config().heartbeatIntervalNs();
    }

    private void requestTimeReply(long t1, long t2) {
        peer.lock.lock();
        try {
            requests.timeReply(t1, t2);
            peer.work.signal();
        } finally {
            peer.lock.unlock();
        }
    }

    void requestAck() {
        request(requests::requestAck);
    }

    void requestProbe() {
        request(requests::requestProbe);
    }

    private void request(Runnable flag) {
        Peer owner = peer;
        owner.lock.lock();
        try {
            flag.run();
            owner.work.signal();
        } finally {
            owner.lock.unlock();
        }
    }

    /** Whether acknowledgements are owed: messages delivered since the last one sent. */
    boolean owesAck() {
        return peer.inboundCount() > lastAckSent;
    }

    // ---------------------------------------------------------------- identity and closing

    /** The node that dialed this connection. */
    String initiatorId() {
        return dialer != null ? engine.nodeId() : hello.nodeId();
    }

    /**
     * The one-connection rule: keep the connection dialed by the node with the lower id; between
     * two dialed by the same node, the newer (the older is likely dead, which is why it redialed).
     */
    boolean isPreferredOver(Connection other) {
        String lower = engine.nodeId().compareTo(peer.nodeId) < 0 ? engine.nodeId() : peer.nodeId;
        boolean mine = initiatorId().equals(lower);
        boolean theirs = other.initiatorId().equals(lower);
        return mine || !theirs;
    }

    Dialer dialer() {
        return dialer;
    }

    Peer peer() {
        return peer;
    }

    String remote() {
        return remote;
    }

    boolean isActivated() {
        return activated;
    }

    /**
     * Ends the connection, once: counted and logged by reason; the peer's messages wait for the
     * next connection; a BYE says why (unless the peer closed first) before the socket closes.
     */
    void close(CloseReason reason, String detail) {
        synchronized (this) {
            if (closed) {
                return;
            }
            closed = true;
        }
        closing = true;
        if (aborted) {
            // abort() took the socket away: no BYE, nobody to wait for.
            reason = abortReason;
            detail = abortDetail;
        }
        Peer owner = peer;
        boolean wasActive = false;
        boolean sayBye = reason != CloseReason.PEER_CLOSED && !aborted;
        if (owner != null) {
            owner.lock.lock();
            try {
                if (sayBye) {
                    requests.requestBye(reason, detail);
                }
                owner.work.signalAll();
            } finally {
                owner.lock.unlock();
            }
            wasActive = owner.deactivate(this);
        }
        engine.connectionClosed(this, reason, detail, wasActive);
        Thread writing = writerThread;
        Thread current = Thread.currentThread();
        if (writing != null && writing != current) {
            try {
                writing.join(CLOSE_GRACE_MS);
            } catch (InterruptedException e) {
                Thread.currentThread().interrupt();
            }
        } else if (writing == null && current == readerThread && sayBye && writer != null) {
            try {
                Frame.Reject refusal = requests.pendingReject(); // this thread set it, before any writer
                if (refusal != null) {
                    writer.reject(refusal.seq(), refusal.reason());
                }
                writer.bye(reason.code(), detail);
                writer.flush();
                socket.shutdownOutput();
            } catch (IOException | RuntimeException e) {
                // The peer is gone or never was one; the socket closes below either way.
            }
        }
        if (current == readerThread && (reason.isBadInput() || reason == CloseReason.DUPLICATE)) {
            drainInput();
        } else if (current != readerThread && writing != null && sayBye) {
            // Let the reader read on until the peer, having read the BYE, closes its side: closing
            // with unread input would reset the connection and could destroy the BYE.
            try {
                readerThread.join(CLOSE_GRACE_MS);
            } catch (InterruptedException e) {
                Thread.currentThread().interrupt();
            }
        }
        try {
            socket.close();
        } catch (IOException e) {
            // Closing anyway.
        }
        engine.connectionEnded(this, wasActive, reason);
    }

    private volatile boolean aborted;
    private volatile CloseReason abortReason;
    private volatile String abortDetail;

    /**
     * Ends the connection at once, without BYE or waiting for its threads (a peer that reads
     * nothing, or a pending handshake pushed out): the socket closes on a thread of its own (a TLS
     * close may try to write), which wakes this connection's threads to finish the close.
     */
    void abort(CloseReason reason, String detail) {
        synchronized (this) {
            if (closed || aborted) {
                return;
            }
            abortReason = reason;
            abortDetail = detail;
            aborted = true;
        }
        closing = true;
        Thread.ofPlatform().daemon().name("etherware-net-" + engine.nodeId() + "-abort").start(() -> {
            try {
                socket.close();
            } catch (IOException e) {
                // Closed either way.
            }
            close(reason, detail); // once: whichever of this and the woken threads comes first
        });
    }

    /**
     * Reads and discards what the peer still sends, until it closes or the grace runs out: closing
     * with unread input would reset the connection and could destroy the BYE before it is read.
     */
    private void drainInput() {
        long deadlineNs = engine.nowNs() + TimeUnit.MILLISECONDS.toNanos(CLOSE_GRACE_MS);
        try {
            InputStream input = socket.getInputStream();
            byte[] sink = new byte[4096];
            while (true) {
                long leftMs = TimeUnit.NANOSECONDS.toMillis(deadlineNs - engine.nowNs());
                if (leftMs <= 0) {
                    return;
                }
                socket.setSoTimeout((int) leftMs);
                if (input.read(sink) < 0) {
                    return;
                }
            }
        } catch (IOException e) {
            // Timed out or reset: done draining.
        }
    }

    @Override
    public String toString() {
        return "connection " + engine.nodeId() + "<->" + (hello != null ? hello.nodeId() : "?") + " (" + remote
                + (dialer != null ? ", dialed" : ", accepted") + ")";
    }
}
