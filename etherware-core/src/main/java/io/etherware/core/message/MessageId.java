package io.etherware.core.message;

import java.util.Objects;

/**
 * Identity of a message, unique within the node that created it: the node id plus a sequence
 * number that node never reuses while it runs. Its text form is {@code node#sequence}.
 *
 * @param nodeId   the creating node's id (see {@link Profile} for the allowed characters)
 * @param sequence the node-local sequence number, &gt;= 0
 */
public record MessageId(String nodeId, long sequence) {

    /**
     * Checks the node id and the sequence.
     *
     * @throws IllegalArgumentException if {@code nodeId} does not match
     *                                  {@link Profile#NAME_PATTERN} or {@code sequence} is negative
     */
    public MessageId {
        Objects.requireNonNull(nodeId, "nodeId");
        if (!Profile.isName(nodeId)) {
            throw new IllegalArgumentException("nodeId='" + nodeId + "' must match " + Profile.NAME_PATTERN);
        }
        if (sequence < 0) {
            throw new IllegalArgumentException("sequence=" + sequence + " must be >= 0");
        }
    }

    /**
     * Parses {@code node#sequence}, the form {@link #toString()} produces.
     *
     * @param text the text form
     * @return the id it names
     * @throws IllegalArgumentException naming the text if it is not of that form, its node id is
     *                                  malformed or its sequence is not a number &gt;= 0
     */
    public static MessageId parse(String text) {
        Objects.requireNonNull(text, "text");
        int hash = text.lastIndexOf('#');
        if (hash <= 0 || hash == text.length() - 1) {
            throw new IllegalArgumentException("message id '" + text + "' is not of the form node#sequence");
        }
        long sequence;
        try {
            sequence = Long.parseLong(text, hash + 1, text.length(), 10);
        } catch (NumberFormatException e) {
            throw new IllegalArgumentException("message id '" + text + "' has a sequence that is not a number", e);
        }
        return new MessageId(text.substring(0, hash), sequence);
    }

    @Override
    public String toString() {
        return nodeId + "#" + sequence;
    }
}
