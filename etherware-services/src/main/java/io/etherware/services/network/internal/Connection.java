package io.etherware.services.network.internal;

import io.etherware.services.network.CloseReason;
import java.io.IOException;
import java.io.InputStream;
import java.net.Socket;
import java.net.SocketTimeoutException;
import java.util.concurrent.TimeUnit;
import javax.net.ssl.SSLException;

/**
 * One TCP connection to another node: the handshake, then a reader (the thread that ran the
 * handshake) and a writer thread. The reader runs the {@link ConnectionInput}, which hands messages
 * to the kernel in stream order and answers control frames through the writer; the writer sends
 * what its lane's {@link Link} has, most critical first, and flushes once per turn, so a burst
 * leaves in few system calls.
 *
 * <p>A dead or slow peer blocks only this connection's two threads; a sender never waits for it:
 * it writes its frame itself only while the connection is idle (its socket's buffer has room, see
 * {@link Link}), and queues otherwise.
 *
 * <p>Thread-safety: the writer requests are guarded by the link's lock; {@link #close} may be
 * called from any thread, once takes effect.
 */
final class Connection implements Runnable {

    /** How long a closing connection waits for its writer to say BYE, and drains the input. */
    private static final long CLOSE_GRACE_MS = 500;
    /** Most messages a writer takes in one turn. */
    private static final int BATCH = 64;
    private static final int DIRECT_BUDGET_MAX_BYTES = 64 * 1024;

    private final NetworkContext context;
    private final ConnectionEvents events;
    private final Socket socket;
    private final Dialer dialer;
    private final String remote;
    /** The lane this connection carries: the dialer's, or the one the dialing peer's HELLO names. */
    private volatile int lane;
    private volatile Peer peer;
    /** The peer's link of this lane, once the HELLO said who the peer is. */
    private volatile Link link;
    private Frame.Hello hello;
    /** The node id the connection authenticated (TLS), or null on a plain link. */
    private String authenticatedId;
    private FrameReader reader;
    private FrameWriter writer;
    private volatile Thread readerThread;
    private volatile Thread writerThread;
    private volatile boolean closing;
    private volatile boolean activated;
    /** The peer's BYE was read: it closed on purpose, its process did not just end. */
    private volatile boolean goodbyeRead;
    /** Guarded by this: {@link #close} runs once. */
    private boolean closed;

    /** What the writer is asked to send besides messages; guarded by the link's lock. */
    final WriterRequests requests = new WriterRequests();

    /** The output side, once the handshake has written its frames. */
    private volatile ConnectionOutput output;

    // Control thread only.
    long nextProbeNs;
    int probesSent;

    /**
     * @param dialer the dialer that opened it, or null for an accepted connection
     */
    Connection(NetworkContext context, ConnectionEvents events, Socket socket, Dialer dialer) {
        this.context = context;
        this.events = events;
        this.socket = socket;
        this.dialer = dialer;
        this.lane = dialer != null ? dialer.lane : 0;
        this.remote = String.valueOf(socket.getRemoteSocketAddress());
        this.nextProbeNs = NetworkContext.nowNs();
    }

    // ---------------------------------------------------------------- the reader thread

    @Override
    public void run() {
        readerThread = Thread.currentThread();
        try {
            handshake();
        } catch (ProtocolException e) {
            context.counters().handshakesFailed.increment();
            close(e.reason(), e.getMessage());
            return;
        } catch (SocketTimeoutException e) {
            context.counters().handshakesFailed.increment();
            close(CloseReason.HANDSHAKE_TIMEOUT, "no handshake within "
                    + TimeUnit.NANOSECONDS.toMillis(context.config().handshakeTimeoutNs()) + " ms");
            return;
        } catch (IOException e) {
            context.counters().handshakesFailed.increment();
            close(closing ? CloseReason.SHUTDOWN : CloseReason.IO_ERROR, "handshake failed: " + e);
            return;
        } finally {
            events.handshakeEnded(this);
        }
        if (!activated) {
            return;
        }
        Thread writing = new ConnectionThread(this::writeLoop, "etherware-net-" + context.nodeId() + "-write-"
                + laneName());
        writerThread = writing;
        writing.start();
        new ConnectionInput(this, context, events, reader, peer, link, lane, hello.incarnation(), authenticatedId != null,
                output).readLoop();
    }

    private void handshake() throws IOException {
        socket.setTcpNoDelay(true);
        socket.setKeepAlive(true);
        socket.setSoTimeout((int) Math.max(1, TimeUnit.NANOSECONDS.toMillis(context.config().handshakeTimeoutNs())));
        try {
            authenticatedId = context.config().connectionFactory().authenticate(socket).orElse(null);
        } catch (SocketTimeoutException e) {
            throw e;
        } catch (SSLException e) {
            throw new ProtocolException(CloseReason.AUTHENTICATION_FAILED, "TLS handshake failed: " + e.getMessage(), e);
        }
        reader = new FrameReader(socket.getInputStream(), context.config().maxFrameBytes());
        writer = new FrameWriter(socket.getOutputStream());
        int lanes = context.lanes().size();
        writer.hello(new Frame.Hello(Frame.VERSION, context.nodeId(), context.incarnation(),
                context.kernel().clock().epochNanos(), context.acceptedFrameBytes(), lanes, lane));
        writer.flush();
        hello = reader.readHello();
        long helloArrivedEpochNs = context.kernel().clock().epochNanos();
        if (authenticatedId != null && !authenticatedId.equals(hello.nodeId())) {
            throw new ProtocolException(CloseReason.AUTHENTICATION_FAILED, "the peer's certificate names node '"
                    + authenticatedId + "' but its HELLO says '" + hello.nodeId() + "'");
        }
        if (hello.nodeId().equals(context.nodeId())) {
            throw new ProtocolException(CloseReason.BAD_HANDSHAKE, "the peer has this node's id '" + hello.nodeId()
                    + "': node ids must be unique (or a node dialed itself)");
        }
        if (hello.lanes() != lanes) {
            throw new ProtocolException(CloseReason.BAD_HANDSHAKE, "node '" + hello.nodeId() + "' runs "
                    + hello.lanes() + " lanes per pair of nodes, this node " + lanes
                    + ": give every node the same NetworkConfig.lanes");
        }
        if (dialer == null) {
            lane = hello.lane();
        } else {
            dialer.identified(hello.nodeId());
        }
        peer = events.peer(hello.nodeId());
        link = peer.link(lane);
        writer.resume(link.resumeState());
        writer.flush();
        Frame second = reader.next();
        if (second instanceof Frame.Bye goodbye) {
            // The peer may leave at any time, also inside its handshake (it is shutting down, or its
            // side of the connection failed): that is a close, not bad input.
            throw new ProtocolException(CloseReason.PEER_CLOSED, "node '" + hello.nodeId() + "' closed the connection"
                    + " during the handshake: " + CloseReason.ofCode(goodbye.code()) + ": " + goodbye.text());
        }
        if (!(second instanceof Frame.Resume theirs)) {
            throw new ProtocolException(CloseReason.BAD_HANDSHAKE, "expected RESUME after HELLO, got "
                    + second.getClass().getSimpleName());
        }
        // A quarter of the send buffer: the kernel counts its own overhead against the rest.
        output = new ConnectionOutput(writer, context, link, peer.nodeId,
                Math.min(hello.maxFrameBytes(), context.config().maxFrameBytes()),
                Math.min(DIRECT_BUDGET_MAX_BYTES, socket.getSendBufferSize() / 4));
        Thread.currentThread().setName("etherware-net-" + context.nodeId() + "-read-" + laneName());
        events.handshakeEnded(this); // no longer a pending handshake that a flood could push out
        activated = events.activate(this, hello, theirs, helloArrivedEpochNs);
        socket.setSoTimeout((int) Math.max(1, TimeUnit.NANOSECONDS.toMillis(context.config().heartbeatTimeoutNs())));
    }

    // ---------------------------------------------------------------- the writer thread

    private void writeLoop() {
        context.lanes().get(lane).configureCurrent();
        try {
            while (true) {
                WriterTurn turn = link.nextTurn(this, BATCH);
                if (turn == null) {
                    return;
                }
                try {
                    output.write(this, turn);
                    if (turn.isLast()) {
                        socket.shutdownOutput();
                        return;
                    }
                } finally {
                    link.endTurn();
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

    // ---------------------------------------------------------------- writer requests (under link.lock)

    /** Asks the writer to answer a time request that arrived at {@code t2}. */
    void requestTimeReply(long t1, long t2) {
        link.lock.lock();
        try {
            requests.timeReply(t1, t2);
            link.work.signal();
        } finally {
            link.lock.unlock();
        }
    }

    /**
     * Asks the writer to send REJECT for a message frame refused for good; not signalled: the
     * close that follows wakes the writer.
     */
    void requestReject(Frame.Reject reject) {
        link.lock.lock();
        try {
            requests.reject(reject);
        } finally {
            link.lock.unlock();
        }
    }

    void requestAck() {
        request(requests::requestAck);
    }

    void requestProbe() {
        request(requests::requestProbe);
    }

    private void request(Runnable flag) {
        Link owner = link;
        owner.lock.lock();
        try {
            flag.run();
            owner.work.signal();
        } finally {
            owner.lock.unlock();
        }
    }

    // ---------------------------------------------------------------- identity and closing

    /** The node that dialed this connection. */
    String initiatorId() {
        return dialer != null ? context.nodeId() : hello.nodeId();
    }

    /**
     * The one-connection rule: keep the connection dialed by the node with the lower id; between
     * two dialed by the same node, the newer (the older is likely dead, which is why it redialed).
     */
    boolean isPreferredOver(Connection other) {
        String lower = context.nodeId().compareTo(peer.nodeId) < 0 ? context.nodeId() : peer.nodeId;
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

    Link link() {
        return link;
    }

    /** The writer thread, once the connection is established. */
    Thread writerThread() {
        return writerThread;
    }

    /** The output side (null before the handshake wrote its frames). */
    ConnectionOutput output() {
        return output;
    }

    int lane() {
        return lane;
    }

    /** The peer's id, and the lane when there are several: for thread names. */
    private String laneName() {
        return context.lanes().size() == 1 ? peer.nodeId : peer.nodeId + "-lane" + lane;
    }

    String remote() {
        return remote;
    }

    boolean isActivated() {
        return activated;
    }

    /** Whether the connection is closing: its threads stop at the next frame or wait. */
    boolean isClosing() {
        return closing;
    }

    /** The reader read the peer's BYE. */
    void goodbyeRead() {
        goodbyeRead = true;
    }

    /**
     * Whether the peer ended this connection without a goodbye: end of stream or a socket error
     * without its BYE before, as when its process exits (its system closes the socket) or its host
     * resets the connection. A heartbeat timeout (a silent peer, or a partition) is not one.
     */
    boolean endedWithoutGoodbye(CloseReason reason) {
        return !goodbyeRead && (reason == CloseReason.PEER_CLOSED || reason == CloseReason.IO_ERROR);
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
        Link owner = link;
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
        events.connectionClosed(this, reason, detail, wasActive);
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
        events.connectionEnded(this, wasActive, reason);
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
        Thread.ofPlatform().daemon().name("etherware-net-" + context.nodeId() + "-abort").start(() -> {
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
        long deadlineNs = NetworkContext.nowNs() + TimeUnit.MILLISECONDS.toNanos(CLOSE_GRACE_MS);
        try {
            InputStream input = socket.getInputStream();
            byte[] sink = new byte[4096];
            while (true) {
                long leftMs = TimeUnit.NANOSECONDS.toMillis(deadlineNs - NetworkContext.nowNs());
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
        return "connection " + context.nodeId() + "<->" + (hello != null ? hello.nodeId() : "?") + " (" + remote
                + (dialer != null ? ", dialed" : ", accepted") + ")";
    }
}
