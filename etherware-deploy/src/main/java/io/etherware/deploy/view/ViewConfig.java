package io.etherware.deploy.view;

import java.net.InetSocketAddress;
import java.util.Objects;

/**
 * Where a {@link NodeView} listens. Loopback by default: the view tells anyone who can connect
 * the node's components, peers and signals, and authenticates no one, so an address beyond
 * loopback must be chosen on purpose ({@code allowRemote}). Immutable, checked when built.
 *
 * @param listen      the address to bind; port 0 takes any free port
 * @param allowRemote whether {@code listen} may be beyond loopback
 */
public record ViewConfig(InetSocketAddress listen, boolean allowRemote) {

    /**
     * Checks the address.
     *
     * @throws IllegalArgumentException for an unresolved address, or one beyond loopback without
     *                                  {@code allowRemote}
     */
    public ViewConfig {
        Objects.requireNonNull(listen, "listen");
        if (listen.isUnresolved()) {
            throw new IllegalArgumentException("listen=" + listen + " does not resolve; write an address");
        }
        if (!allowRemote && !listen.getAddress().isLoopbackAddress()) {
            throw new IllegalArgumentException("listen=" + listen.getAddress().getHostAddress() + ":"
                    + listen.getPort() + " is beyond loopback, and the view authenticates no one: listen on"
                    + " 127.0.0.1 (and reach it through an SSH tunnel), or allow it on purpose with"
                    + " allowRemote=\"true\" on a network you trust");
        }
    }

    /**
     * A view on loopback.
     *
     * @param port the port, 0 for any free one
     * @return the configuration
     */
    public static ViewConfig loopback(int port) {
        return new ViewConfig(new InetSocketAddress("127.0.0.1", port), false);
    }
}
