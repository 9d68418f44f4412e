package io.etherware.services.notifier;

import io.etherware.core.message.Contents;

/**
 * A request to the Notifier's component ({@code notifier.unsubscribe}): no more Ticks for the
 * named subscription. Answered with a {@link NotifierReply}, refused if the name is unknown.
 * Immutable.
 *
 * @param name the subscription's name
 */
public record TickUnsubscribe(String name) implements Contents {

}
