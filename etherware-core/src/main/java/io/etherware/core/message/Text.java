package io.etherware.core.message;

import java.util.Objects;

/**
 * Free text contents, registered as {@code text}.
 *
 * @param text any Unicode text; never null
 */
public record Text(String text) implements Contents {
    /**
     * Checks that there is a text.
     *
     * @throws NullPointerException if {@code text} is null
     */
    public Text {
        Objects.requireNonNull(text, "text");
    }
}
