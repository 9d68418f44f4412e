package io.etherware.core.kernel;

import io.etherware.core.message.Contents;

/**
 * A marker another node puts in its stream of messages to a component, to learn when everything
 * it sent the component before it is queued at the node hosting the component; registered as
 * {@code order-marker}. It travels as any message to the component's profile (forwarded by a node
 * the component left, behind the sender's earlier messages); the kernel that finds the component
 * hosted (or nothing at all) under the profile makes no job of it and never hands it to the
 * component: it answers the node the marker came from (its
 * {@link io.etherware.core.message.Message#origin()}, the connection's word, never a profile the
 * message names) with a message carrying the same token, to that node's profile. From there on
 * the kernel keeps the order of what the sender sent before and after, through holds and moves.
 * A marker made on the node itself is not answered.
 *
 * <p>The network messenger uses it to keep a sender's order when a component moves to another
 * node: see NETWORK-PROTOCOL.md, "Order across a move".
 *
 * @param token the sender's token, returned in the answer
 */
public record OrderMarker(long token) implements Contents {
}
