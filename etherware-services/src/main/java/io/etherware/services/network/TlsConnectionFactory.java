package io.etherware.services.network;

import io.etherware.core.message.Profile;
import java.io.IOException;
import java.io.InputStream;
import java.net.InetSocketAddress;
import java.net.ServerSocket;
import java.net.Socket;
import java.nio.file.Files;
import java.nio.file.Path;
import java.security.GeneralSecurityException;
import java.security.KeyStore;
import java.security.cert.Certificate;
import java.security.cert.X509Certificate;
import java.util.ArrayList;
import java.util.Collections;
import java.util.List;
import java.util.Objects;
import java.util.Optional;
import javax.net.ssl.KeyManagerFactory;
import javax.net.ssl.SSLContext;
import javax.net.ssl.SSLParameters;
import javax.net.ssl.SSLPeerUnverifiedException;
import javax.net.ssl.SSLServerSocket;
import javax.net.ssl.SSLSocket;
import javax.net.ssl.TrustManagerFactory;
import javax.security.auth.x500.X500Principal;

/**
 * Mutual TLS 1.3 between nodes, with the JDK's own TLS: every connection authenticates both
 * ends with certificates that chain to the deployment's CA, and a node's identity is the common
 * name (CN) of its certificate's subject, which must equal its node id. The messenger then
 * refuses a HELLO that names another node than the certificate, so no peer can speak for a node
 * whose key it does not hold.
 *
 * <p>Host names are not checked (nodes are identified by node id, not by address); the CA is the
 * only trust anchor, so the trust store should hold the deployment's CA and nothing else (not
 * the JDK's public CAs). How to make a CA and node certificates with {@code keytool} is in the
 * README's Security section.
 *
 * <p>Thread-safe and immutable after construction.
 */
public final class TlsConnectionFactory implements ConnectionFactory {

    private static final String[] PROTOCOLS = {"TLSv1.3"};

    private final SSLContext context;
    private final String localNodeId;

    private TlsConnectionFactory(SSLContext context, String localNodeId) {
        this.context = context;
        this.localNodeId = localNodeId;
    }

    /**
     * A factory from PKCS#12 files: {@code keyStore} holds exactly one private key with this
     * node's certificate chain, {@code trustStore} the deployment CA's certificate. Reads the files
     * now; call it at configuration time.
     *
     * @param keyStore           this node's PKCS#12 key store (CN of the certificate = node id)
     * @param keyStorePassword   the key store's (and key's) password
     * @param trustStore         the PKCS#12 trust store with the deployment CA's certificate
     * @param trustStorePassword the trust store's password
     * @return the factory
     * @throws IOException naming the file and what was wrong with it
     */
    public static TlsConnectionFactory fromPkcs12(Path keyStore, char[] keyStorePassword, Path trustStore,
                                                  char[] trustStorePassword) throws IOException {
        KeyStore keys = load(keyStore, keyStorePassword, "keyStore");
        KeyStore trusted = load(trustStore, trustStorePassword, "trustStore");
        return of(keys, keyStorePassword, trusted);
    }

    /**
     * A factory from loaded key stores (e.g. made in memory by a test).
     *
     * @param keyStore    holds exactly one private key, with this node's certificate chain
     * @param keyPassword the password of that key
     * @param trustStore  holds the deployment CA's certificate as a trusted entry
     * @return the factory
     * @throws IOException if the key store does not hold exactly one key whose certificate names a
     *                     node id, the trust store holds no certificate, or TLS cannot be set up
     *                     with them (a wrong key password, say)
     */
    public static TlsConnectionFactory of(KeyStore keyStore, char[] keyPassword, KeyStore trustStore)
            throws IOException {
        Objects.requireNonNull(keyStore, "keyStore");
        Objects.requireNonNull(trustStore, "trustStore");
        try {
            List<String> keyAliases = new ArrayList<>();
            for (String alias : Collections.list(keyStore.aliases())) {
                if (keyStore.isKeyEntry(alias)) {
                    keyAliases.add(alias);
                }
            }
            if (keyAliases.size() != 1) {
                throw new IOException("keyStore holds " + keyAliases.size() + " private keys " + keyAliases
                        + "; it must hold exactly one, this node's");
            }
            Certificate own = keyStore.getCertificate(keyAliases.getFirst());
            if (!(own instanceof X509Certificate x509)) {
                throw new IOException("keyStore entry '" + keyAliases.getFirst() + "' has no X.509 certificate");
            }
            String nodeId = nodeIdOf(x509);
            boolean anyTrusted = false;
            for (String alias : Collections.list(trustStore.aliases())) {
                anyTrusted |= trustStore.isCertificateEntry(alias);
            }
            if (!anyTrusted) {
                throw new IOException("trustStore holds no trusted certificate; import the deployment CA's with"
                        + " keytool -importcert");
            }
            var keyManagers = KeyManagerFactory.getInstance(KeyManagerFactory.getDefaultAlgorithm());
            keyManagers.init(keyStore, keyPassword);
            var trustManagers = TrustManagerFactory.getInstance("PKIX");
            trustManagers.init(trustStore);
            SSLContext context = SSLContext.getInstance("TLSv1.3");
            context.init(keyManagers.getKeyManagers(), trustManagers.getTrustManagers(), null);
            return new TlsConnectionFactory(context, nodeId);
        } catch (GeneralSecurityException e) {
            throw new IOException("cannot set up TLS: " + e.getMessage(), e);
        }
    }

    private static KeyStore load(Path file, char[] password, String field) throws IOException {
        Objects.requireNonNull(file, field);
        if (!Files.isRegularFile(file)) {
            throw new IOException(field + "=" + file + " is not a file");
        }
        try (InputStream in = Files.newInputStream(file)) {
            KeyStore store = KeyStore.getInstance("PKCS12");
            store.load(in, password);
            return store;
        } catch (GeneralSecurityException | IOException e) {
            throw new IOException(field + "=" + file + " cannot be read as a PKCS#12 key store (wrong password?): "
                    + e.getMessage(), e);
        }
    }

    /**
     * The node id a certificate names: its subject's single CN, which must be a valid node id.
     *
     * @param certificate a node's certificate
     * @return the CN of its subject
     * @throws SSLPeerUnverifiedException if there is no such CN
     */
    public static String nodeIdOf(X509Certificate certificate) throws SSLPeerUnverifiedException {
        String subject = certificate.getSubjectX500Principal().getName(X500Principal.RFC2253);
        String found = null;
        for (String part : subject.split(",")) {
            if (part.regionMatches(true, 0, "CN=", 0, 3)) {
                if (found != null) {
                    throw new SSLPeerUnverifiedException("certificate subject '" + subject
                            + "' has more than one CN; a node certificate names one node id");
                }
                found = part.substring(3);
            }
        }
        if (found == null || !Profile.isName(found)) {
            throw new SSLPeerUnverifiedException("certificate subject '" + subject + "' names no node id: its CN"
                    + " must match " + Profile.NAME_PATTERN);
        }
        return found;
    }

    @Override
    public ServerSocket listen(InetSocketAddress address) throws IOException {
        var server = (SSLServerSocket) context.getServerSocketFactory().createServerSocket();
        server.setEnabledProtocols(PROTOCOLS);
        server.setNeedClientAuth(true);
        return Sockets.bind(server, address);
    }

    @Override
    public Socket connect(InetSocketAddress address, int timeoutMs) throws IOException {
        var socket = (SSLSocket) context.getSocketFactory().createSocket();
        SSLParameters parameters = socket.getSSLParameters();
        parameters.setProtocols(PROTOCOLS);
        parameters.setEndpointIdentificationAlgorithm(null); // identity is the node id, checked after
        socket.setSSLParameters(parameters);
        return Sockets.connect(socket, address, timeoutMs);
    }

    /** Completes the TLS handshake and returns the node id of the peer's certificate. */
    @Override
    public Optional<String> authenticate(Socket socket) throws IOException {
        if (!(socket instanceof SSLSocket ssl)) {
            throw new SSLPeerUnverifiedException("not a TLS socket: " + socket);
        }
        ssl.startHandshake();
        Certificate[] chain = ssl.getSession().getPeerCertificates();
        if (chain.length == 0 || !(chain[0] instanceof X509Certificate leaf)) {
            throw new SSLPeerUnverifiedException("the peer presented no X.509 certificate");
        }
        return Optional.of(nodeIdOf(leaf));
    }

    @Override
    public boolean authenticatesPeers() {
        return true;
    }

    @Override
    public Optional<String> localNodeId() {
        return Optional.of(localNodeId);
    }

    @Override
    public String toString() {
        return "mutual TLS 1.3 as node '" + localNodeId + "'";
    }
}
