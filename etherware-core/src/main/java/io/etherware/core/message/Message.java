package io.etherware.core.message;

import java.util.Objects;

/**
 * An Etherware message (paper Fig. 1 and Fig. 3): whom it is for, when it was made, how it must
 * be delivered and what it says.
 *
 * <p>Immutable. In process it is passed by reference and never serialized; it becomes XML only
 * where it leaves the JVM (the network, state snapshots, logs on request).
 *
 * @param profile       the receiver's profile (exact or a query the registry resolves)
 * @param sender        the sender's profile, to which replies go; null when the sender is not a
 *                      component (a test, a main method)
 * @param timeStamp     creation time, epoch nanoseconds of the sender node's clock; translated
 *                      by NetworkTime when the message crosses nodes
 * @param qos           delivery requirements; {@link QoS#NONE} for best effort
 * @param contents      the payload, a registered record; {@link Empty#INSTANCE} for none
 * @param messageId     unique within the creating node
 * @param correlationId for a reply, the id of the request it answers; otherwise null
 * @param origin        for a message that arrived from another node, where it came from as the
 *                      network layer established it (see {@link Origin}); null for a message made
 *                      on this node. Never serialized: each node sets it from the connection.
 */
public record Message(Profile profile, Profile sender, long timeStamp, QoS qos, Contents contents,
                      MessageId messageId, MessageId correlationId, Origin origin) {

    /**
     * Checks the required components.
     *
     * @throws NullPointerException if {@code profile}, {@code qos}, {@code contents} or
     *                              {@code messageId} is null
     */
    public Message {
        Objects.requireNonNull(profile, "profile");
        Objects.requireNonNull(qos, "qos");
        Objects.requireNonNull(contents, "contents");
        Objects.requireNonNull(messageId, "messageId");
    }

    /**
     * A message made on this node (no {@link #origin()}).
     *
     * @param profile       the receiver's profile (exact or a query)
     * @param sender        the sender's profile, or null when the sender is not a component
     * @param timeStamp     creation time, epoch nanoseconds of this node's clock
     * @param qos           delivery requirements; {@link QoS#NONE} for best effort
     * @param contents      the payload, a registered record
     * @param messageId     a new id of this node
     * @param correlationId for a reply, the id of the request it answers; otherwise null
     * @throws NullPointerException if {@code profile}, {@code qos}, {@code contents} or
     *                              {@code messageId} is null
     */
    public Message(Profile profile, Profile sender, long timeStamp, QoS qos, Contents contents, MessageId messageId,
                   MessageId correlationId) {
        this(profile, sender, timeStamp, qos, contents, messageId, correlationId, null);
    }

    /** {@return whether this message answers a request (it has a correlation id)} */
    public boolean isReply() {
        return correlationId != null;
    }

    /** {@return whether a reply can be sent to this message's sender} */
    public boolean hasSender() {
        return sender != null;
    }

    /**
     * {@return this message with another receiver, e.g. after a query was resolved}
     *
     * @param newProfile the new receiver's profile
     */
    public Message withProfile(Profile newProfile) {
        return new Message(newProfile, sender, timeStamp, qos, contents, messageId, correlationId, origin);
    }

    /**
     * {@return this message with its time stamp translated into another clock (NetworkTime)}
     *
     * @param newTimeStamp the creation time in epoch nanoseconds of the other clock
     */
    public Message withTimeStamp(long newTimeStamp) {
        return new Message(profile, sender, newTimeStamp, qos, contents, messageId, correlationId, origin);
    }

    /**
     * {@return this message as received from the network through {@code newOrigin}} For the
     * network layer, which alone knows the connection.
     *
     * @param newOrigin where it came from, as the connection established it
     */
    public Message withOrigin(Origin newOrigin) {
        return new Message(profile, sender, timeStamp, qos, contents, messageId, correlationId, newOrigin);
    }

    /** {@return whether this message was made on this node (it did not arrive from the network)} */
    public boolean isLocal() {
        return origin == null;
    }

    /**
     * The contents cast to the expected type.
     *
     * @param <T>  the expected contents type
     * @param type the expected contents record class
     * @return the contents as {@code type}
     * @throws ClassCastException naming both types if the contents are of another type
     */
    public <T extends Contents> T contentsAs(Class<T> type) {
        if (!type.isInstance(contents)) {
            throw new ClassCastException("message " + messageId + " carries " + contents.getClass().getSimpleName()
                    + ", not " + type.getSimpleName());
        }
        return type.cast(contents);
    }
}
