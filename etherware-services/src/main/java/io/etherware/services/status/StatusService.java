package io.etherware.services.status;

import io.etherware.core.component.Component;
import io.etherware.core.component.ComponentContext;
import io.etherware.core.kernel.EtherwareNode;
import io.etherware.core.message.Message;
import io.etherware.services.network.NetworkMessenger;

/**
 * Answers {@link StatusRequest}s with the node's {@link NodeStatus}, at
 * {@code etherware.status[node=<id>]}: what the control tool asks a running node. Read-only; it
 * answers every node that can reach it, so a node whose links authenticate no one (plain TCP) tells
 * its status to whoever connects on loopback, and with TLS only to the deployment's nodes. Other
 * contents are answered with nothing and logged once.
 */
public final class StatusService implements Component {

    private final EtherwareNode node;
    private final NetworkMessenger network;
    private boolean warned;

    private StatusService(EtherwareNode node, NetworkMessenger network) {
        this.node = node;
        this.network = network;
    }

    /**
     * Adds the status service to {@code node}.
     *
     * @param node    the node
     * @param network its messenger, for the peers in the status, or null if it has none
     */
    public static void install(EtherwareNode node, NetworkMessenger network) {
        Status.registerContents(node.contentsTypes());
        node.add(Status.profileOf(node.nodeId()), () -> new StatusService(node, network));
    }

    @Override
    public void onMessage(Message message, ComponentContext context) {
        if (message.contents() instanceof StatusRequest) {
            context.reply(message, Status.snapshot(node, network));
        } else if (!warned) {
            warned = true;
            context.logger().warn("status service of {}: ignored {} from {} (it answers status requests only;"
                    + " logged once)", node.nodeId(), message.contents().getClass().getSimpleName(), message.sender());
        }
    }
}
