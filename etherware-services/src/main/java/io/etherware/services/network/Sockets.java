package io.etherware.services.network;

import java.io.IOException;
import java.net.InetSocketAddress;
import java.net.ServerSocket;
import java.net.Socket;

/** Binding and connecting the sockets a {@link ConnectionFactory} made, closing them on failure. */
final class Sockets {

    private Sockets() {
    }

    /** Binds {@code server} (address reuse on, backlog 64), or closes it and throws. */
    static <S extends ServerSocket> S bind(S server, InetSocketAddress address) throws IOException {
        try {
            server.setReuseAddress(true);
            server.bind(address, 64);
            return server;
        } catch (IOException e) {
            server.close();
            throw e;
        }
    }

    /** Connects {@code socket} with TCP_NODELAY, or closes it and throws. */
    static <S extends Socket> S connect(S socket, InetSocketAddress address, int timeoutMs) throws IOException {
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
