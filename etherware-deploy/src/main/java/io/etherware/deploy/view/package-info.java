/**
 * A live view of a running node, opt-in and on loopback by default: a
 * {@link io.etherware.deploy.view.NodeView} serves a page, the node's status as JSON and a
 * Prometheus endpoint on the JDK's HTTP server; {@link io.etherware.deploy.view.LiveSignals} are
 * the time series components publish for it to plot.
 */
package io.etherware.deploy.view;
