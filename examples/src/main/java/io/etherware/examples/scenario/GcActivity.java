package io.etherware.examples.scenario;

import java.lang.management.GarbageCollectorMXBean;
import java.lang.management.ManagementFactory;

/**
 * The garbage collector's work as the JVM counts it: collections and their accumulated time over
 * every collector. Subtract two readings to get a run's share. Immutable.
 *
 * @param collections collections so far
 * @param timeMs      their accumulated time in milliseconds, as the JVM reports it
 */
public record GcActivity(long collections, long timeMs) {

    /** The collectors' counts now. */
    public static GcActivity now() {
        long count = 0;
        long time = 0;
        for (GarbageCollectorMXBean bean : ManagementFactory.getGarbageCollectorMXBeans()) {
            count += Math.max(0, bean.getCollectionCount());
            time += Math.max(0, bean.getCollectionTime());
        }
        return new GcActivity(count, time);
    }

    /** The work done since {@code earlier}. */
    public GcActivity since(GcActivity earlier) {
        return new GcActivity(collections - earlier.collections, timeMs - earlier.timeMs);
    }
}
