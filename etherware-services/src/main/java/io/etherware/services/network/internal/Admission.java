package io.etherware.services.network.internal;

import io.etherware.services.network.CloseReason;
import java.util.List;
import java.util.Set;
import java.util.concurrent.ConcurrentHashMap;
import java.util.concurrent.ConcurrentLinkedDeque;
import org.slf4j.Logger;
import org.slf4j.LoggerFactory;

/**
 * The messenger's connections and their limits: at most {@code maxConnections} established, and
 * a budget of {@code maxPendingHandshakes} in their handshake beyond which the oldest pending one is
 * pushed out, so idle connections cannot lock honest peers out (an honest handshake takes
 * milliseconds; a flood's connections wait for the timeout).
 *
 * <p>Thread-safety: any thread.
 */
final class Admission {

    private static final Logger log = LoggerFactory.getLogger("io.etherware.services.network.NetworkMessenger");

    private final NetworkContext context;
    private final Set<Connection> connections = ConcurrentHashMap.newKeySet();
    /** Connections in their handshake, oldest first. */
    private final ConcurrentLinkedDeque<Connection> pending = new ConcurrentLinkedDeque<>();

    Admission(NetworkContext context) {
        this.context = context;
    }

    /** Why a new connection must be refused now, or null if it may come in. */
    String refusal() {
        int max = context.config().maxConnections();
        return connections.size() - pending.size() >= max ? "maxConnections=" + max + " reached" : null;
    }

    /** Takes {@code connection} in, in its handshake, pushing the oldest pending one out beyond the budget. */
    void admit(Connection connection) {
        connections.add(connection);
        pending.addLast(connection);
        int budget = context.config().maxPendingHandshakes();
        while (pending.size() > budget) {
            Connection oldest = pending.pollFirst();
            if (oldest == null) {
                break;
            }
            if (oldest.isActivated()) {
                continue; // finished its handshake just now
            }
            long evicted = context.counters().handshakesEvicted.incrementAndGet();
            if (evicted == 1 || evicted % 1000 == 0) {
                log.warn("node {}: more than maxPendingHandshakes={} connections in their handshake; closing the"
                        + " oldest ({} so far; a flood of idle connections?)", context.nodeId(), budget, evicted);
            }
            oldest.abort(CloseReason.HANDSHAKE_EVICTED, "pushed out by newer connections: maxPendingHandshakes="
                    + budget + " reached");
        }
    }

    /** The connection's handshake is over, either way. */
    void handshakeEnded(Connection connection) {
        pending.remove(connection);
    }

    /** The connection's socket is closed. */
    void ended(Connection connection) {
        connections.remove(connection);
        pending.remove(connection);
    }

    /** Every connection now. */
    List<Connection> all() {
        return List.copyOf(connections);
    }
}
