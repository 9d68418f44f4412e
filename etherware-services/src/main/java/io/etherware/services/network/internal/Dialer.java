package io.etherware.services.network.internal;

import io.etherware.services.network.CloseReason;
import java.io.IOException;
import java.net.InetSocketAddress;
import java.net.Socket;
import java.util.concurrent.ThreadLocalRandom;
import java.util.concurrent.TimeUnit;
import org.slf4j.Logger;
import org.slf4j.LoggerFactory;

/**
 * Keeps one lane to a configured peer address connected: dials when no connection of its lane to
 * the node there is up,
 * and redials with exponential backoff and jitter after a refusal or a loss.
 *
 * <p>Thread-safety: {@link #maybeDial} runs on the control thread; the attempt runs on its own
 * connection thread and reports back through the synchronized methods.
 */
final class Dialer {

    private static final Logger log = LoggerFactory.getLogger(Dialer.class);

    final InetSocketAddress address;
    /** The lane its connections carry. */
    final int lane;
    private final Engine engine;
    private final Backoff backoff;
    /** The node found at the address by the last handshake, or null before one. */
    private volatile String nodeId;
    // Guarded by this.
    private boolean attempting;
    private long nextAttemptNs;
    private int failuresInARow;

    Dialer(Engine engine, InetSocketAddress address, int lane) {
        this.engine = engine;
        this.address = address;
        this.lane = lane;
        this.backoff = new Backoff(engine.config().reconnectInitialBackoffNs(), engine.config().reconnectMaxBackoffNs(),
                engine.config().reconnectJitter(), ThreadLocalRandom.current());
        this.nextAttemptNs = engine.nowNs();
    }

    /** Starts an attempt if none runs, the node there is not connected and the backoff has passed. */
    void maybeDial(long nowNs) {
        synchronized (this) {
            if (attempting || nowNs - nextAttemptNs < 0 || (nodeId != null && engine.isConnected(nodeId, lane))) {
                return;
            }
            attempting = true;
        }
        var attempt = new ConnectionThread(this::attempt, "etherware-net-" + engine.nodeId() + "-dial-" + address + "-lane" + lane);
        attempt.start();
    }

    private void attempt() {
        Socket socket;
        try {
            socket = engine.config().connectionFactory().connect(address,
                    (int) Math.max(1, TimeUnit.NANOSECONDS.toMillis(engine.config().connectTimeoutNs())));
        } catch (IOException | RuntimeException e) {
            failed("cannot connect: " + e.getMessage());
            return;
        }
        Connection connection = engine.open(socket, this);
        if (connection != null) {
            connection.run(); // handshake, then read until it ends; ended() reports back
        } else {
            failed("refused locally: too many connections or closing");
        }
    }

    /** The node at the address said who it is: no need to dial it while it is connected. */
    void identified(String peerId) {
        nodeId = peerId;
    }

    /** The connection from this dialer completed its handshake with {@code peerId}. */
    synchronized void activated(String peerId) {
        nodeId = peerId;
        backoff.reset();
        if (failuresInARow > 0) {
            log.info("node {}: connected to node '{}' at {} after {} failed attempts", engine.nodeId(), peerId, address,
                    failuresInARow);
        }
        failuresInARow = 0;
    }

    /** The connection from this dialer ended (or never completed its handshake). */
    synchronized void ended(boolean wasActivated, CloseReason reason) {
        if (!wasActivated && reason != CloseReason.DUPLICATE) {
            failed("no handshake (" + reason + ")");
            return;
        }
        attempting = false;
        nextAttemptNs = engine.nowNs() + backoff.nextDelayNs();
    }

    private synchronized void failed(String why) {
        attempting = false;
        long delayNs = backoff.nextDelayNs();
        nextAttemptNs = engine.nowNs() + delayNs;
        failuresInARow++;
        if (failuresInARow == 1) {
            log.info("node {}: peer at {}: {}; redialing with backoff (next in {} ms)", engine.nodeId(), address, why,
                    TimeUnit.NANOSECONDS.toMillis(delayNs));
        } else {
            log.debug("node {}: peer at {}: {} (attempt {}); next in {} ms", engine.nodeId(), address, why,
                    failuresInARow, TimeUnit.NANOSECONDS.toMillis(delayNs));
        }
    }

    String nodeId() {
        return nodeId;
    }
}
