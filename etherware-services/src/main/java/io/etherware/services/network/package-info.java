/**
 * The NetworkMessenger (paper Section III-C): TCP between nodes, profile announcements and
 * routes, criticality-ordered bounded outbound queues, acknowledged streams that survive
 * reconnection, and the {@link io.etherware.services.network.ConnectionFactory} seam for TLS.
 * The wire protocol is described in {@code NETWORK-PROTOCOL.md}; the machinery lives in the
 * unexported {@code internal} package.
 */
package io.etherware.services.network;
