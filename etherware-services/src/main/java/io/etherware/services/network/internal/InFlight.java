package io.etherware.services.network.internal;

/**
 * A message written to a peer and not yet acknowledged: kept, with its encoding, until the peer
 * says its kernel has it, so that it can be sent again on a new connection or reported lost.
 *
 * @param seq      its place in the stream
 * @param outgoing the message
 * @param xml      its encoding, sent again as it is
 */
record InFlight(long seq, Outgoing outgoing, byte[] xml) {
}
