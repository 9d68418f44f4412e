package io.etherware.core.kernel;

/**
 * The node's answer when a component fails more often than its {@link SupervisionPolicy} allows
 * (the root of the Management Tree).
 */
public enum Escalation {
    /**
     * Reset every component, each at its own message boundary: stop it, make a fresh instance,
     * start it, forget its restart history. The Management Tree's reset.
     */
    RESET_ALL,
    /** Close the node: drain or discard what is queued and stop every component. */
    STOP_NODE
}
