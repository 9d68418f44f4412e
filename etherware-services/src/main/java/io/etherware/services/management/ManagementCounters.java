package io.etherware.services.management;

import java.util.concurrent.atomic.LongAdder;

/**
 * What a management service counts, shared by the instances that its supervision's restarts make
 * (see {@link ManagementService#install}); read by its public count methods.
 *
 * <p>Thread-safety: any thread (adders).
 */
final class ManagementCounters {
    final LongAdder upgraded = new LongAdder();
    final LongAdder migrated = new LongAdder();
    final LongAdder migratedIn = new LongAdder();
    final LongAdder abandonedIn = new LongAdder();
    final LongAdder takenOverIn = new LongAdder();
    final LongAdder failed = new LongAdder();
    final LongAdder refused = new LongAdder();
    final LongAdder busy = new LongAdder();
}
