package io.etherware.services.network;

import io.etherware.core.message.Contents;
import io.etherware.core.message.ContentsTypes;

/** Test contents: one number. Registered in the shared registry as {@code net-test-num}. */
public record Num(long value) implements Contents {

    static {
        ContentsTypes.shared().register("net-test-num", Num.class);
    }

    /** Makes sure the static registration ran. */
    static void register() {
    }
}
