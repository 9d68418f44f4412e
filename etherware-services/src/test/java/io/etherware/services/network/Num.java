package io.etherware.services.network;

import io.etherware.core.message.Contents;
import io.etherware.core.message.ContentsTypes;

/** Test contents: one number, on the wire as {@code net-test-num}. */
public record Num(long value) implements Contents {

    /** Registers {@code Num} in {@code types}; returns {@code types}. */
    static ContentsTypes register(ContentsTypes types) {
        return types.register("net-test-num", Num.class);
    }
}
