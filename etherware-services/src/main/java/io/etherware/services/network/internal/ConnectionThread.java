package io.etherware.services.network.internal;

/** A platform daemon thread of the messenger: a connection's reader or writer, or a dial attempt. */
final class ConnectionThread extends Thread {

    ConnectionThread(Runnable task, String name) {
        super(task, name);
        setDaemon(true);
    }
}
