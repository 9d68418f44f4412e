package io.etherware.core.kernel;

import io.etherware.core.message.Message;

/**
 * Sees every message a node is asked to deliver ({@link Kernel#send}): made here, arrived from
 * the network, replies; before the kernel resolves it. A recorder uses it
 * ({@code io.etherware.services.recording.Recorder}). Added with {@link EtherwareNode#tap}.
 *
 * <p>Threading contract: called on the sending thread, often a dispatcher or a network reader, so
 * it must be quick and must not block: copy the reference and hand it to a thread of your own.
 * An exception it throws is logged once and otherwise ignored; the message is delivered anyway.
 */
@FunctionalInterface
public interface MessageTap {

    /**
     * One message the node is about to deliver.
     *
     * @param message the message as sent, its profile as the sender addressed it
     */
    void seen(Message message);

    /** A tap's registration with a node; closing it removes the tap. */
    interface Registration extends AutoCloseable {

        /** Removes the tap: it sees no message sent after this returns. Idempotent. */
        @Override
        void close();
    }
}
