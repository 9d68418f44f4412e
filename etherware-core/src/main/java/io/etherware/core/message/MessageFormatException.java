package io.etherware.core.message;

/**
 * A message could not be encoded or decoded: malformed or hostile XML, an unregistered contents
 * type, a field that does not fit its record. The text says what was wrong and where, so the
 * log line alone is enough to find the sender's bug.
 */
public class MessageFormatException extends RuntimeException {
    /**
     * A failure without an underlying exception.
     *
     * @param message what was wrong and where
     */
    public MessageFormatException(String message) {
        super(message);
    }

    /**
     * A failure caused by a parser's or writer's exception.
     *
     * @param message what was wrong and where
     * @param cause   the underlying exception
     */
    public MessageFormatException(String message, Throwable cause) {
        super(message, cause);
    }
}
