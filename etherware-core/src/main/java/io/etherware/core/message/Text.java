package io.etherware.core.message;

import java.util.Objects;

/**
 * Free text contents, registered as {@code text}.
 *
 * @param text any Unicode text; never null
 */
public record Text(String text) implements Contents {
    public Text {
        Objects.requireNonNull(text, "text");
    }
}
