package io.etherware.core.kernel;

import io.etherware.core.message.Contents;
import java.util.Objects;

/**
 * The kernel's notice that a message could not be delivered, sent to the message's sender as a
 * reply to it (its correlation id is the lost message's id). Registered as {@code undeliverable}.
 * A request that is undeliverable fails its future instead.
 *
 * @param profile   the receiver profile of the lost message, in text form
 * @param messageId the lost message's id, {@code node#sequence}
 * @param reason    why, e.g. no matching component, an ambiguous query with its candidates
 */
public record Undeliverable(String profile, String messageId, String reason) implements Contents {
    /**
     * Checks that every component is given.
     *
     * @throws NullPointerException if a component is null
     */
    public Undeliverable {
        Objects.requireNonNull(profile, "profile");
        Objects.requireNonNull(messageId, "messageId");
        Objects.requireNonNull(reason, "reason");
    }
}
