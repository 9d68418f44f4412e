package io.etherware.services.network.internal;

import io.etherware.core.message.Criticality;
import io.etherware.core.message.Message;
import io.etherware.core.message.MessageFormatException;

/**
 * What a message must pass before a lane to a peer takes it (its hops within {@code maxHops}, its
 * encoding within the peer's frame limit), and what becomes of messages a full queue evicts or
 * refuses (NETWORK-PROTOCOL.md, "Bounds"; design decision 14). Runs on the sender's thread.
 *
 * <p>Thread-safety: immutable; takes no lock (its link calls it outside its own).
 */
final class OutboundRules {

    private final String nodeId;
    private final NetworkContext context;

    /** @param nodeId the peer the lane leads to */
    OutboundRules(String nodeId, NetworkContext context) {
        this.nodeId = nodeId;
        this.context = context;
    }

    /** The hops {@code message} makes on this lane, or an exception the kernel reports to the sender. */
    int hops(Message message) {
        // A message that came from the network is relayed: one more hop than it had made.
        int hops = message.origin() == null ? 0 : message.origin().hops() + 1;
        if (hops > context.config().maxHops()) {
            throw new IllegalStateException("message " + message.messageId() + " was already relayed " + (hops - 1)
                    + " times (maxHops=" + context.config().maxHops() + "): the nodes' routes disagree");
        }
        return hops;
    }

    /**
     * The message's XML, within the frame limit of {@code connection}'s peer (or this node's own
     * limit when none is connected), or an exception the kernel reports to the sender.
     */
    byte[] encode(Message message, Connection connection) {
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

    /**
     * Reports what the queue did with {@code message} beyond queueing it: the less critical
     * messages it evicted are dropped (counted); if it did not fit, a NONE or LOW message is
     * dropped and a MIDDLE or HIGH one refused by throwing, which the kernel turns into an
     * undeliverable notice to its sender.
     */
    void overflowed(Message message, OutboundQueue.Outcome outcome) {
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
}
