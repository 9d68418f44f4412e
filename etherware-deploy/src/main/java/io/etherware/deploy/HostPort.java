package io.etherware.deploy;

import java.net.Inet6Address;
import java.net.InetSocketAddress;

/**
 * The {@code HOST:PORT} text of addresses, as deployment files, the launcher and the control tool
 * write and read them: the host a name, an IPv4 address, or an IPv6 address in brackets.
 * Stateless.
 */
final class HostPort {

    private HostPort() {
    }

    /**
     * Parses and resolves {@code text}.
     *
     * @param text {@code HOST:PORT}
     * @return the resolved address
     * @throws IllegalArgumentException saying what is wrong: no port, a port that is not a number or
     *                                  above 65535, or a host that does not resolve
     */
    static InetSocketAddress parse(String text) {
        int colon = text.lastIndexOf(':');
        String host = colon <= 0 ? text : text.substring(0, colon);
        int port;
        try {
            if (colon <= 0) {
                throw new NumberFormatException("no port");
            }
            port = Integer.parseInt(text.substring(colon + 1));
        } catch (NumberFormatException e) {
            throw new IllegalArgumentException("'" + text + "' is not HOST:PORT (" + e.getMessage() + ")", e);
        }
        if (port < 0 || port > 65_535) {
            throw new IllegalArgumentException("port " + port + " is above 65535");
        }
        if (host.startsWith("[") && host.endsWith("]")) {
            host = host.substring(1, host.length() - 1);
        }
        var address = new InetSocketAddress(host, port);
        if (address.isUnresolved()) {
            throw new IllegalArgumentException("host '" + host + "' does not resolve; check the name or write an"
                    + " address");
        }
        return address;
    }

    /**
     * {@code address} as {@link #parse} reads it back.
     *
     * @param address a resolved address
     * @return {@code HOST:PORT}, an IPv6 address in brackets
     */
    static String format(InetSocketAddress address) {
        String host = address.getAddress() instanceof Inet6Address ipv6 ? "[" + ipv6.getHostAddress() + "]"
                : address.getHostString();
        return host + ":" + address.getPort();
    }
}
