package io.etherware.services.network.internal;

import io.etherware.core.message.Message;

/**
 * A message waiting to go to a peer, with the number of nodes that relayed it on its way here.
 *
 * @param message the message
 * @param hops    0 when it was sent on this node, else the relays it went through
 * @param xml     its encoding, made by the sending thread when it was handed over
 * @param after   for a NONE message on lane 1, how many messages of lane 0's stream must be
 *                acknowledged (or lane 0 drained) before it goes: those queued for the peer
 *                before it; -1 for any other
 */
record Outgoing(Message message, int hops, byte[] xml, long after) {

    /** Whether it is NONE or LOW: shed from a full queue, and bounded in flight (see {@link Peer}). */
    boolean isSheddable() {
        return message.qos().criticality().compareTo(io.etherware.core.message.Criticality.LOW) <= 0;
    }

    /** Its criticality as an index, least critical first. */
    int level() {
        return message.qos().criticality().ordinal();
    }
}
