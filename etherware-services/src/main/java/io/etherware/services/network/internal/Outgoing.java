package io.etherware.services.network.internal;

import io.etherware.core.message.Message;

/**
 * A message waiting to go to a peer, with the number of nodes that relayed it on its way here.
 *
 * @param message the message
 * @param hops    0 when it was sent on this node, else the relays it went through
 * @param xml     its encoding, made by the sending thread when it was handed over
 */
record Outgoing(Message message, int hops, byte[] xml) {

    /** Whether it is NONE or LOW: shed from a full queue, and bounded in flight (see {@link Peer}). */
    boolean isSheddable() {
        return message.qos().criticality().compareTo(io.etherware.core.message.Criticality.LOW) <= 0;
    }

    /** Its criticality as an index, least critical first. */
    int level() {
        return message.qos().criticality().ordinal();
    }
}
