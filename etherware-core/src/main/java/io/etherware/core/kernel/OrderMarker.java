package io.etherware.core.kernel;

import io.etherware.core.message.Contents;

/**
 * A marker another node puts in its stream of messages to a component, to learn when everything
 * it sent the component before it has been handled; registered as {@code order-marker}. It travels
 * as any message to the component's profile (forwarded, kept during a hold, moved with a
 * migration, queued behind the sender's earlier messages of the same urgency); when its turn
 * comes the kernel hosting the component does not hand it to the component but answers the node
 * it came from (its {@link io.etherware.core.message.Message#origin()}, never a profile the
 * message names) with a reply carrying the same token, to that node's profile.
 *
 * <p>The network messenger uses it to keep a sender's order when a component moves to another
 * node: see NETWORK-PROTOCOL.md, "Order across a move".
 *
 * @param token the sender's token, returned in the answer
 */
public record OrderMarker(long token) implements Contents {
}
