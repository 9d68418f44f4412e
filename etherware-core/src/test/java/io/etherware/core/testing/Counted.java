package io.etherware.core.testing;

import io.etherware.core.component.ComponentState;

/** Test state: a counter. */
public record Counted(long count) implements ComponentState {
}
