package io.etherware.services.network.internal;

import io.etherware.services.network.CloseReason;
import io.etherware.services.network.NetworkStats;
import java.util.EnumMap;
import java.util.concurrent.atomic.LongAdder;

/** The messenger's counters; {@link LongAdder}s, so any thread counts without contention. */
final class Counters {

    final LongAdder sent = new LongAdder();
    final LongAdder resent = new LongAdder();
    final LongAdder received = new LongAdder();
    final LongAdder duplicates = new LongAdder();
    final LongAdder overflowDropped = new LongAdder();
    final LongAdder undeliverable = new LongAdder();
    final LongAdder opened = new LongAdder();
    final LongAdder handshakesFailed = new LongAdder();
    final LongAdder announcementsRefused = new LongAdder();
    final LongAdder inboundPauses = new LongAdder();
    final LongAdder routeFlushes = new LongAdder();
    final LongAdder routeFlushTimeouts = new LongAdder();
    final java.util.concurrent.atomic.AtomicLong handshakesEvicted = new java.util.concurrent.atomic.AtomicLong();
    private final LongAdder[] closes = new LongAdder[CloseReason.values().length];

    Counters() {
        for (int i = 0; i < closes.length; i++) {
            closes[i] = new LongAdder();
        }
    }

    void closed(CloseReason reason) {
        closes[reason.ordinal()].increment();
    }

    NetworkStats snapshot(String nodeId, int connectedPeers) {
        var byReason = new EnumMap<CloseReason, Long>(CloseReason.class);
        for (CloseReason reason : CloseReason.values()) {
            long count = closes[reason.ordinal()].sum();
            if (count > 0) {
                byReason.put(reason, count);
            }
        }
        return new NetworkStats(nodeId, connectedPeers, sent.sum(), resent.sum(), received.sum(), duplicates.sum(),
                overflowDropped.sum(), undeliverable.sum(), opened.sum(), handshakesFailed.sum(), byReason,
                announcementsRefused.sum(), inboundPauses.sum(), routeFlushes.sum(), routeFlushTimeouts.sum());
    }
}
