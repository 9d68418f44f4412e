package io.etherware.services.network.internal;

import io.etherware.core.message.Message;

/**
 * A message waiting to go to a peer, with the number of nodes that relayed it on its way here.
 *
 * @param message the message
 * @param hops    0 when it was sent on this node, else the relays it went through
 * @param xml     its encoding, made by the sending thread when it was handed over
 * @param after      for a NONE message on lane 1, the generation of lane 0 whose messages (those
 *                   queued for the peer before it) must all be settled before it goes; -1 for any
 *                   other (see {@link Generations})
 * @param generation its own lane's generation when it was taken, to settle it by
 */
record Outgoing(Message message, int hops, byte[] xml, long after, long generation) {

    /** Whether it is NONE or LOW: shed from a full queue, and bounded in flight on one lane (see {@link OutboundStream}). */
    boolean isSheddable() {
        return message.qos().criticality().compareTo(io.etherware.core.message.Criticality.LOW) <= 0;
    }

    /** Its criticality as an index, least critical first. */
    int level() {
        return message.qos().criticality().ordinal();
    }
}
