package io.etherware.core.kernel;

import io.etherware.core.message.Message;

/**
 * The way to a profile hosted on another node, registered in the {@link ProfileRegistry} by a
 * transport such as the NetworkMessenger. {@link Kernel#send} hands a message for that profile
 * to {@link #deliver} instead of a local dispatcher.
 *
 * <p>Threading contract: {@link #deliver} is called on the sending thread, often a dispatcher, so
 * it must not block: queue the message and return. Throwing tells the kernel the message could
 * not be taken; the sender then gets an {@code undeliverable} notice.
 */
@FunctionalInterface
public interface RemoteRoute {

    /** Takes the message for transmission. Must not block. */
    void deliver(Message message);
}
