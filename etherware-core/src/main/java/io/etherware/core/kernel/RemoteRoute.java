package io.etherware.core.kernel;

import io.etherware.core.message.Message;

/**
 * The way to a profile hosted on another node, registered in the {@link ProfileRegistry} by a
 * transport such as the NetworkMessenger. {@link Kernel#send} hands a message for that profile
 * to {@link #deliver} instead of a local dispatcher.
 *
 * <p>Threading contract: {@link #deliver} is called on the sending thread, often a dispatcher, so
 * it must not block: queue the message and return. Throwing tells the kernel the message could
 * not be taken; the sender then gets an {@code undeliverable} notice.
 */
@FunctionalInterface
public interface RemoteRoute {

    /**
     * Takes the message for transmission. Must not block.
     *
     * @param message the message for a profile this route was registered for
     * @throws RuntimeException any, if the message cannot be taken; the kernel counts it as
     *                          undeliverable and tells its sender
     */
    void deliver(Message message);

    /**
     * Whether node {@code nodeId} is one this route leads to (or may lead to next, e.g. a node
     * waiting to take a profile over): a reply from the network to a request sent along this route
     * is taken only from such a node, so no third node can answer or fail another's requests. The
     * default, for routes that do not know their nodes, accepts any.
     *
     * @param nodeId the node that made a reply: its
     *               {@link io.etherware.core.message.Origin#nodeId() origin's node id}
     * @return whether a reply from that node may answer a request sent along this route
     */
    default boolean isServedBy(String nodeId) {
        return true;
    }
}
