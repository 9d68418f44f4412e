/** The NetworkMessenger's machinery: frames, connections, peers, routes. Not exported. */
package io.etherware.services.network.internal;
