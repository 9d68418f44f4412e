package io.etherware.services.network;

import java.io.IOException;
import java.net.InetSocketAddress;
import java.net.ServerSocket;
import java.net.Socket;

/**
 * Makes the sockets a {@link NetworkMessenger} talks through: the seam where TLS goes (an
 * implementation returning {@code SSLServerSocket}s and {@code SSLSocket}s) without touching the
 * messenger. The messenger sets TCP_NODELAY, keep-alive and timeouts on what it gets.
 *
 * <p>Thread-safety: implementations must be thread-safe; the messenger calls {@link #connect}
 * from its dialing threads. Both methods may block (that is what those threads are for).
 */
public interface ConnectionFactory {

    /** A server socket bound to {@code address} (port 0: an ephemeral port). */
    ServerSocket listen(InetSocketAddress address) throws IOException;

    /** A socket connected to {@code address}, giving up after {@code timeoutMs}. */
    Socket connect(InetSocketAddress address, int timeoutMs) throws IOException;

    /** Plain TCP. */
    static ConnectionFactory plain() {
        return PlainTcp.INSTANCE;
    }

    /** Plain TCP sockets from {@code java.net}. */
    enum PlainTcp implements ConnectionFactory {
        INSTANCE;

        @Override
        public ServerSocket listen(InetSocketAddress address) throws IOException {
            var server = new ServerSocket();
            try {
                server.setReuseAddress(true);
                server.bind(address, 64);
                return server;
            } catch (IOException e) {
                server.close();
                throw e;
            }
        }

        @Override
        public Socket connect(InetSocketAddress address, int timeoutMs) throws IOException {
            var socket = new Socket();
            try {
                socket.setTcpNoDelay(true);
                socket.connect(address, timeoutMs);
                return socket;
            } catch (IOException e) {
                socket.close();
                throw e;
            }
        }
    }
}
