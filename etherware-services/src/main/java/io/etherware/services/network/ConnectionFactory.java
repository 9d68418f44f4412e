package io.etherware.services.network;

import java.io.IOException;
import java.net.InetSocketAddress;
import java.net.ServerSocket;
import java.net.Socket;
import java.nio.file.Path;
import java.util.Optional;

/**
 * Makes the sockets a {@link NetworkMessenger} talks through, and says who is at the other end:
 * {@link #tls} authenticates both nodes of every connection with certificates whose identity is
 * their node id (mutual TLS); {@link #plain()} authenticates nobody and is meant for loopback
 * development (a messenger refuses it beyond loopback unless configured
 * {@link NetworkConfig.Builder#insecure insecure}). The messenger sets TCP_NODELAY, keep-alive and
 * timeouts on what it gets.
 *
 * <p>Thread-safety: implementations must be thread-safe; the messenger calls {@link #connect}
 * from its dialing threads. Both methods may block (that is what those threads are for).
 */
public interface ConnectionFactory {

    /**
     * A server socket bound to {@code address}. Called once, when the messenger starts.
     *
     * @param address the listen address (port 0: an ephemeral port)
     * @return the bound server socket
     * @throws IOException if the address cannot be bound
     */
    ServerSocket listen(InetSocketAddress address) throws IOException;

    /**
     * A socket connected to {@code address}. Called on a dialing thread; may block up to
     * {@code timeoutMs}.
     *
     * @param address   the peer's listen address
     * @param timeoutMs how long the connect may take, in milliseconds, &gt;= 1
     * @return the connected socket
     * @throws IOException if the connection is refused, unreachable or times out
     */
    Socket connect(InetSocketAddress address, int timeoutMs) throws IOException;

    /**
     * Authenticates the peer of a connection, before anything else is read or written on it:
     * for TLS, completes the handshake and returns the node id the peer's certificate names.
     * Called once per connection, on the connection's own thread, with the socket's read timeout
     * set to the handshake timeout.
     *
     * @param socket the connection, accepted or dialed through this factory
     * @return the authenticated node id, or empty if this factory does not authenticate peers
     * @throws IOException if the peer cannot be authenticated (the connection is closed)
     */
    default Optional<String> authenticate(Socket socket) throws IOException {
        return Optional.empty();
    }

    /**
     * Whether {@link #authenticate} establishes who the peer is (a node id from a certificate).
     *
     * @return false by default; true lets a messenger use addresses beyond loopback
     */
    default boolean authenticatesPeers() {
        return false;
    }

    /**
     * The node id this node's own credentials name, if the factory has any: the messenger refuses
     * to start when it differs from the node's id.
     *
     * @return the node id, or empty (the default) for a factory without credentials
     */
    default Optional<String> localNodeId() {
        return Optional.empty();
    }

    /**
     * Plain TCP: no encryption, no authentication; for loopback development.
     *
     * @return the shared plain-TCP factory
     */
    static ConnectionFactory plain() {
        return PlainTcp.INSTANCE;
    }

    /**
     * Mutual TLS 1.3 from PKCS#12 key stores (see {@link TlsConnectionFactory}).
     *
     * @param keyStore           this node's private key and certificate chain (CN = its node id)
     * @param keyStorePassword   the key store's (and key's) password
     * @param trustStore         the certificates of the deployment's CA, which every node's
     *                           certificate must chain to
     * @param trustStorePassword the trust store's password
     * @return the factory, which authenticates peers
     * @throws IOException naming the file and what was wrong with it (see
     *                     {@link TlsConnectionFactory#fromPkcs12})
     */
    static ConnectionFactory tls(Path keyStore, char[] keyStorePassword, Path trustStore, char[] trustStorePassword)
            throws IOException {
        return TlsConnectionFactory.fromPkcs12(keyStore, keyStorePassword, trustStore, trustStorePassword);
    }

    /** Plain TCP sockets from {@code java.net}. */
    enum PlainTcp implements ConnectionFactory {
        /** The only instance; stateless. */
        INSTANCE;

        @Override
        public ServerSocket listen(InetSocketAddress address) throws IOException {
            return Sockets.bind(new ServerSocket(), address);
        }

        @Override
        public Socket connect(InetSocketAddress address, int timeoutMs) throws IOException {
            return Sockets.connect(new Socket(), address, timeoutMs);
        }
    }
}
