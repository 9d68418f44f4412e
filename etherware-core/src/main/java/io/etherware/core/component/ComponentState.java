package io.etherware.core.component;

import io.etherware.core.message.Contents;

/**
 * The state of a component at a message boundary (the Memento of the paper's component model).
 *
 * <p>A state is a record registered in {@link io.etherware.core.message.ContentsTypes} like any
 * message contents, so the codec can write it as XML and a migration can ship it to another node
 * inside a message. It must therefore be immutable and hold only values the codec can write
 * (numbers, strings, booleans, enums, lists and nested records of those).
 *
 * <p>Thread-safety: records are immutable and safe to share.
 */
public interface ComponentState extends Contents {

    /**
     * The version of this state's layout. Raise it when the record changes incompatibly, so an
     * upgraded component's {@link Component#restore} can tell old state from new and convert it.
     *
     * @return the layout version, 1 unless overridden
     */
    default int schemaVersion() {
        return 1;
    }
}
