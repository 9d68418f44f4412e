package io.etherware.services.notifier;

import io.etherware.core.message.Contents;
import io.etherware.core.message.Profile;

/**
 * A request to the Notifier's component ({@code notifier.retarget}): send the named
 * subscription's Ticks to {@code target} from the next release on, keeping its release times and
 * sequence (a migrated component keeps its rhythm). Answered with a {@link NotifierReply}.
 * Immutable.
 *
 * @param name   the subscription's name
 * @param target the new target profile
 */
public record TickRetarget(String name, Profile target) implements Contents {

}
