package io.etherware.services.network.internal;

import io.etherware.services.network.CloseReason;

/**
 * What a connection tells the messenger that owns it; called on the connection's threads (or
 * a closer's), never with a link's lock held.
 */
interface ConnectionEvents {
    /** The node this HELLO came from (made on first contact). */
    Peer peer(String nodeId);

    /** The handshake is over, either way: the connection no longer counts as pending. */
    void handshakeEnded(Connection connection);

    /** After the handshake: make the connection its lane's, or close it (a duplicate); true if made. */
    boolean activate(Connection connection, Frame.Hello hello, Frame.Resume theirs, long helloArrivedEpochNs);

    /** The routes or connections changed: wake whoever waits for them. */
    void stateChanged();

    /** The active connection of one of the peer's lanes, of the peer's {@code incarnation}, brought an ANNOUNCE. */
    void announced(Peer peer, long incarnation, Frame.Announce announce);

    /** The peer said BYE SHUTDOWN on its lane's connection. */
    void peerShutDown(Peer peer);

    /** The connection closed, and why (counted and logged). */
    void connectionClosed(Connection connection, CloseReason reason, String detail, boolean wasActive);

    /** Its socket is closed. */
    void connectionEnded(Connection connection, boolean wasActive, CloseReason reason);
}
