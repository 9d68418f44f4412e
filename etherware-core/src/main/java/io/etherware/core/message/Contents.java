package io.etherware.core.message;

/**
 * The payload of a {@link Message} (paper Fig. 1, "Contents").
 *
 * <p>Every payload type is a record that implements this interface and is registered by name in
 * {@link ContentsTypes}; the name, never a Java class name, is what travels on the wire. Records
 * are immutable, so one instance may be delivered to several components and threads.
 */
public interface Contents {
}
