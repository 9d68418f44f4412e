package io.etherware.services.notifier;

import io.etherware.core.message.Contents;

/**
 * The Notifier's answer ({@code notifier.reply}) to {@link TickSubscribe}, {@link TickUnsubscribe}
 * and {@link TickRetarget}. Immutable.
 *
 * @param name           the subscription concerned (null if the request was too malformed to say)
 * @param accepted       whether the request took effect
 * @param firstReleaseNs for an accepted subscribe: its first release on the Notifier node's
 *                       monotonic clock; otherwise null
 * @param reason         why it was refused, naming the field; null when accepted
 */
public record NotifierReply(String name, boolean accepted, Long firstReleaseNs, String reason) implements Contents {

    static NotifierReply accepted(String name, Long firstReleaseNs) {
        return new NotifierReply(name, true, firstReleaseNs, null);
    }

    static NotifierReply refused(String name, String reason) {
        return new NotifierReply(name, false, null, reason);
    }
}
