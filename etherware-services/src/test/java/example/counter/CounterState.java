package example.counter;

import io.etherware.core.component.ComponentState;

/**
 * Test state of the counters: messages handled so far and the last sequence number seen.
 * Schema version 2, so tests can see the version handed to the new logic.
 */
public record CounterState(long count, long lastSequence) implements ComponentState {

    public static final int SCHEMA_VERSION = 2;

    @Override
    public int schemaVersion() {
        return SCHEMA_VERSION;
    }
}
