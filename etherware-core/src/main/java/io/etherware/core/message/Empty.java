package io.etherware.core.message;

/** Contents of a message that carries no data, registered as {@code empty}. */
public record Empty() implements Contents {
    /** The one instance worth using. */
    public static final Empty INSTANCE = new Empty();
}
