/**
 * NetworkTime (paper Section III-C): clock offsets to peer nodes from four-timestamp exchanges,
 * minimum-delay filtered with drift following, and the translation of message time stamps into
 * this node's clock.
 */
package io.etherware.services.time;
