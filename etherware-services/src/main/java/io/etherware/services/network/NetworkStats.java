package io.etherware.services.network;

import java.util.Map;

/**
 * Counters of a {@link NetworkMessenger}, read at one moment (each exact; not read atomically
 * together). Immutable; a snapshot.
 *
 * @param nodeId               this node
 * @param connectedPeers       peers with a connection now
 * @param messagesSent         message frames written (first transmissions)
 * @param messagesResent       message frames written again on a new connection because the old one
 *                             ended before the peer acknowledged them
 * @param messagesReceived     messages from peers handed to the kernel
 * @param duplicatesDropped    message frames received twice (after a reconnection), dropped
 * @param overflowDropped      messages of criticality NONE or LOW dropped because a peer's queue
 *                             was full (shed load: counted, senders not told)
 * @param undeliverable        messages the messenger could not deliver and reported: their senders
 *                             got an {@code undeliverable} notice (or, without a sender, a log
 *                             line): refused by a full queue, evicted MIDDLE messages, a peer gone
 *                             for longer than the grace period or restarted before acknowledging,
 *                             a message that does not encode or that the peer refused
 * @param connectionsOpened    connections that completed the handshake and became a peer's
 *                             connection
 * @param handshakesFailed     connections closed before completing the handshake
 * @param closes               connections ended, by reason (bad input among them, see
 *                             {@link CloseReason#isBadInput()})
 * @param announcementsRefused profiles peers announced that this node refused: another node's node
 *                             profile, or one the {@link AnnouncePolicy} does not allow
 * @param inboundPauses        times this node stopped reading from a peer because its messages
 *                             held here reached {@link NetworkConfig#maxInboundBytesPerPeer()}
 * @param routeFlushes         markers this node sent through the old host of a profile that moved,
 *                             each holding its later messages to the profile on one lane until the
 *                             new host had every earlier one (order per sender across a migration)
 * @param routeFlushTimeouts   of those, markers no host answered in time: the lane was released
 *                             anyway (the old host died or dropped the marker), logged
 */
public record NetworkStats(String nodeId, int connectedPeers, long messagesSent, long messagesResent,
                           long messagesReceived, long duplicatesDropped, long overflowDropped, long undeliverable,
                           long connectionsOpened, long handshakesFailed, Map<CloseReason, Long> closes,
                           long announcementsRefused, long inboundPauses, long routeFlushes,
                           long routeFlushTimeouts) {

    /**
     * Copies {@code closes}.
     *
     * @throws NullPointerException if {@code closes} is null or holds null
     */
    public NetworkStats {
        closes = Map.copyOf(closes);
    }

    /**
     * Connections ended for one reason.
     *
     * @param reason the reason
     * @return how many connections ended so, 0 if none
     */
    public long closes(CloseReason reason) {
        return closes.getOrDefault(reason, 0L);
    }

    /**
     * Connections closed because the peer broke the protocol.
     *
     * @return the sum of {@link #closes} over the reasons that are {@link CloseReason#isBadInput()}
     */
    public long badInputCloses() {
        long sum = 0;
        for (Map.Entry<CloseReason, Long> entry : closes.entrySet()) {
            if (entry.getKey().isBadInput()) {
                sum += entry.getValue();
            }
        }
        return sum;
    }
}
