package io.etherware.services.management;

import io.etherware.core.message.Contents;
import io.etherware.core.message.Profile;

/**
 * The answer to a successful {@link UpgradeRequest}, registered as {@code etherware.upgradeResult}:
 * what replaced what, and how long each step took (nanoseconds of the managed node's monotonic
 * clock). A duration the node could not measure is -1.
 *
 * <p>The swap gap is measured by the kernel: from the end of the last message the old logic
 * handled to the start of the first message the new logic handled. It includes any time in which
 * no message was waiting, so under a sparse stream it is up to one period longer than the pause;
 * under a steady backlog it is the pause plus the hand-over to a dispatcher.
 *
 * <p>Immutable; safe to share between threads.
 *
 * @param target             the exact profile of the upgraded component
 * @param oldImplementation  the class name of the logic replaced
 * @param newImplementation  the class name of the logic now running
 * @param source             {@code classpath}, or the canonical path of the jar the class came from
 * @param stateSchemaVersion the schema version of the state handed to the new logic's
 *                           {@code restore}, or -1 if the old logic had no state
 * @param loadNs             loading, checking and constructing the new logic, before the pause
 *                           (off the dispatchers)
 * @param pauseNs            the swap at the message boundary: snapshot, restore, start, swap, stop
 *                           of the old logic; no message is handled meanwhile
 * @param gapNs              the last message handled by the old logic to the first handled by the
 *                           new one; -1 if the old logic had handled none, or no message reached
 *                           the new logic within the service's wait for it
 * @param totalNs            from the request's arrival at the management service to the end of the
 *                           pause (load, wait for the message boundary, pause)
 */
public record UpgradeResult(Profile target, String oldImplementation, String newImplementation, String source,
                            int stateSchemaVersion, long loadNs, long pauseNs, long gapNs, long totalNs)
        implements Contents {

    /** {@link #source()} of a class from the node's class path. */
    public static final String CLASSPATH = "classpath";
}
