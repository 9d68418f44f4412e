package io.etherware.core.testing;

import io.etherware.core.message.Contents;

/** Test contents: one number. */
public record Num(long value) implements Contents {
}
