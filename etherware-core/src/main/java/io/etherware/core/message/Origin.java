package io.etherware.core.message;

import java.util.Objects;

/**
 * Where a message that arrived over the network came from, as this node's network layer
 * established it from authenticated connections, never from text in the message.
 *
 * <p>The rule for relays (a node passing on a message for a component that moved): the node
 * that first received a message from the network checked that its id's node part names the
 * node the connection authenticated; a relay passes that origin on with one more hop, and the
 * next node records the relay as {@code viaNodeId}. So {@code nodeId} of a relayed message is as
 * trustworthy as the relays are: every node of a deployment is authenticated by the same CA. An
 * authorization that must not rest on a relay's word (remote management) requires {@code hops
 * == 0}.
 *
 * @param nodeId    the node that created the message
 * @param viaNodeId the authenticated node whose connection delivered it to this node (equal to
 *                  {@code nodeId} when {@code hops} is 0)
 * @param hops      how many nodes relayed it between {@code nodeId} and this node
 * @param authenticated whether the connection it arrived through authenticated its peer (TLS); a
 *                  plain-TCP connection has only the peer's word for its node id
 * @param wireBytes the size it arrived with (its XML), which the kernel counts against
 *                  {@code viaNodeId} while the message waits in its queues (0: not counted)
 */
public record Origin(String nodeId, String viaNodeId, int hops, boolean authenticated, int wireBytes) {

    /**
     * Checks the components.
     *
     * @throws IllegalArgumentException if {@code hops} or {@code wireBytes} is negative, or
     *                                  {@code hops} is 0 and the two node ids differ
     */
    public Origin {
        Objects.requireNonNull(nodeId, "nodeId");
        Objects.requireNonNull(viaNodeId, "viaNodeId");
        if (hops < 0) {
            throw new IllegalArgumentException("hops=" + hops + " must be >= 0");
        }
        if (wireBytes < 0) {
            throw new IllegalArgumentException("wireBytes=" + wireBytes + " must be >= 0");
        }
        if (hops == 0 && !nodeId.equals(viaNodeId)) {
            throw new IllegalArgumentException("a message received directly (hops=0) comes from its via node: nodeId='"
                    + nodeId + "', viaNodeId='" + viaNodeId + "'");
        }
    }

    /**
     * An origin whose size is not counted ({@code wireBytes} 0).
     *
     * @param nodeId        the node that created the message
     * @param viaNodeId     the authenticated node whose connection delivered it
     * @param hops          how many nodes relayed it, &gt;= 0
     * @param authenticated whether the connection authenticated its peer
     * @throws IllegalArgumentException if {@code hops} is negative, or 0 while the node ids differ
     */
    public Origin(String nodeId, String viaNodeId, int hops, boolean authenticated) {
        this(nodeId, viaNodeId, hops, authenticated, 0);
    }

    /**
     * A message received directly from the node that made it, size not counted.
     *
     * @param nodeId        the peer the connection is with
     * @param authenticated whether the connection authenticated the peer
     * @return an origin with no hops
     */
    public static Origin direct(String nodeId, boolean authenticated) {
        return new Origin(nodeId, nodeId, 0, authenticated);
    }

    /** {@return whether the message came straight from the node that made it} */
    public boolean isDirect() {
        return hops == 0;
    }
}
