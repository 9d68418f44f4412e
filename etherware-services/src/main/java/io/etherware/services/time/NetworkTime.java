package io.etherware.services.time;

import io.etherware.core.message.Message;
import io.etherware.core.time.NodeClock;
import java.time.Duration;
import java.util.ArrayList;
import java.util.Comparator;
import java.util.List;
import java.util.Objects;
import java.util.Optional;
import java.util.concurrent.ConcurrentHashMap;

/**
 * The NetworkTime service (paper Section III-C): estimates, per peer node, the offset between
 * the peer's clock and this node's from NTP-style four-timestamp exchanges, and translates the
 * time stamps of messages arriving from that peer into this node's clock.
 *
 * <p>A transport (the NetworkMessenger) performs the exchanges, stamping them as close to the
 * socket as it can, and feeds them to {@link #onExchange}; this class only filters them (minimum
 * delay over a window, with drift following; see {@link PeerTime}). Offsets are between the
 * nodes' epoch clocks ({@link NodeClock#epochNanos()}), the clock of message time stamps.
 *
 * <p>Thread-safety: all methods may be called from any thread. Reads ({@link #toLocal},
 * {@link #peer}) are lock-free: one map lookup and a volatile read of an immutable estimate.
 */
public final class NetworkTime {

    /** Default number of exchanges the filter looks at. */
    public static final int DEFAULT_WINDOW_SIZE = 16;
    /** Default shortest span of well-measured exchanges before a drift is fitted. */
    public static final Duration DEFAULT_MIN_DRIFT_SPAN = Duration.ofSeconds(1);

    private final NodeClock clock;
    private final int windowSize;
    private final long minDriftSpanNs;
    private final ConcurrentHashMap<String, PeerClock> peers = new ConcurrentHashMap<>();

    /** One peer: its filter (guarded by itself) and the latest estimate, published. */
    private final class PeerClock {
        final OffsetEstimator estimator;
        volatile PeerTime estimate;

        PeerClock(String nodeId) {
            estimator = new OffsetEstimator(nodeId, windowSize, minDriftSpanNs);
        }
    }

    /**
     * NetworkTime with the default window ({@value #DEFAULT_WINDOW_SIZE} exchanges) and drift span
     * (1 s).
     *
     * @param clock this node's clock
     */
    public NetworkTime(NodeClock clock) {
        this(clock, DEFAULT_WINDOW_SIZE, DEFAULT_MIN_DRIFT_SPAN);
    }

    /**
     * NetworkTime with its own filter settings.
     *
     * @param clock          this node's clock
     * @param windowSize     exchanges the filter looks at, 1 to 1024
     * @param minDriftSpan   the shortest time the well-measured exchanges must span before a
     *                       drift is fitted; at least 1 ms
     * @throws IllegalArgumentException if {@code windowSize} or {@code minDriftSpan} is out of range
     */
    public NetworkTime(NodeClock clock, int windowSize, Duration minDriftSpan) {
        this.clock = Objects.requireNonNull(clock, "clock");
        if (windowSize < 1 || windowSize > 1024) {
            throw new IllegalArgumentException("windowSize=" + windowSize + " must be in [1, 1024]");
        }
        Objects.requireNonNull(minDriftSpan, "minDriftSpan");
        if (minDriftSpan.toMillis() < 1) {
            throw new IllegalArgumentException("minDriftSpan=" + minDriftSpan + " must be at least 1 ms");
        }
        this.windowSize = windowSize;
        this.minDriftSpanNs = minDriftSpan.toNanos();
    }

    /**
     * This node's clock.
     *
     * @return the clock given at construction; its epoch time is the local side of every offset
     */
    public NodeClock clock() {
        return clock;
    }

    /**
     * A first guess from a handshake, used until the first exchange: the peer's clock read when it
     * sent, against the local clock when it arrived (off by the one-way delay). Ignored once
     * exchanges have been measured.
     *
     * @param nodeId       the peer
     * @param peerEpochNs  the peer's epoch clock when it sent its handshake, in nanoseconds
     * @param localEpochNs this node's epoch clock when the handshake arrived, in nanoseconds
     */
    public void onHandshake(String nodeId, long peerEpochNs, long localEpochNs) {
        PeerClock peer = peers.computeIfAbsent(nodeId, PeerClock::new);
        synchronized (peer) {
            if (peer.estimate == null || !peer.estimate.isMeasured()) {
                peer.estimate = new PeerTime(nodeId, peerEpochNs - localEpochNs, localEpochNs, 0, -1, -1, 0);
            }
        }
    }

    /**
     * Adds one exchange with {@code nodeId}. Called by the transport, on the thread that received
     * the reply; serialized per peer.
     *
     * @param nodeId the peer
     * @param sample the exchange's four time stamps
     * @return the new estimate, or empty if the exchange was impossible (negative round trip)
     */
    public Optional<PeerTime> onExchange(String nodeId, TimeSample sample) {
        Objects.requireNonNull(sample, "sample");
        PeerClock peer = peers.computeIfAbsent(nodeId, PeerClock::new);
        synchronized (peer) {
            PeerTime estimate = peer.estimator.add(sample);
            if (estimate != null) {
                peer.estimate = estimate;
            }
            return Optional.ofNullable(estimate);
        }
    }

    /**
     * Forgets a peer, e.g. because it restarted with a new clock; its time stamps pass unchanged
     * until it is measured again.
     *
     * @param nodeId the peer
     */
    public void forget(String nodeId) {
        peers.remove(nodeId);
    }

    /**
     * The current estimate for a peer. Lock-free.
     *
     * @param nodeId the peer
     * @return its estimate, or empty if neither a handshake nor an exchange is known
     */
    public Optional<PeerTime> peer(String nodeId) {
        PeerClock peer = peers.get(nodeId);
        return peer == null ? Optional.empty() : Optional.ofNullable(peer.estimate);
    }

    /**
     * The estimates of all peers.
     *
     * @return a new list, sorted by node id
     */
    public List<PeerTime> peers() {
        var all = new ArrayList<PeerTime>();
        for (PeerClock peer : peers.values()) {
            PeerTime estimate = peer.estimate;
            if (estimate != null) {
                all.add(estimate);
            }
        }
        all.sort(Comparator.comparing(PeerTime::nodeId));
        return all;
    }

    /**
     * A time of {@code nodeId}'s epoch clock on this node's epoch clock. Unchanged if nothing is
     * known of that peer yet. Lock-free.
     *
     * @param nodeId      the peer whose clock {@code peerEpochNs} is on
     * @param peerEpochNs a time of the peer's epoch clock, in nanoseconds
     * @return the same instant on this node's epoch clock, in nanoseconds
     */
    public long toLocal(String nodeId, long peerEpochNs) {
        PeerClock peer = peers.get(nodeId);
        PeerTime estimate = peer == null ? null : peer.estimate;
        if (estimate == null) {
            return peerEpochNs;
        }
        // Evaluate the drifting offset at (about) the local time being computed.
        long roughLocalNs = peerEpochNs - estimate.offsetNs();
        return peerEpochNs - estimate.offsetAt(roughLocalNs);
    }

    /**
     * {@code message} from {@code nodeId} with its time stamp on this node's clock. Lock-free.
     *
     * @param nodeId  the peer the message came from
     * @param message the message as the peer stamped it
     * @return a copy of the message with the translated time stamp
     */
    public Message toLocal(String nodeId, Message message) {
        return message.withTimeStamp(toLocal(nodeId, message.timeStamp()));
    }
}
