package io.etherware.services.network.internal;

/**
 * The platform thread that handshakes and then reads one connection. While it hands a message
 * from a peer to the kernel, {@link #inboundHops} holds the hops that message has made, so that
 * a route the kernel passes it on to (a relay) can count one more.
 */
final class ConnectionThread extends Thread {

    /** Hops of the message being handed to the kernel, or -1 outside of that. */
    int inboundHops = -1;

    ConnectionThread(Runnable task, String name) {
        super(task, name);
        setDaemon(true);
    }

    /** The hops of a message sent on the current thread: one more than the inbound, or 0. */
    static int hopsOfCurrentSend() {
        return Thread.currentThread() instanceof ConnectionThread reader && reader.inboundHops >= 0
                ? reader.inboundHops + 1 : 0;
    }
}
