package io.etherware.rt.scheduling.internal;

import io.etherware.core.scheduler.Job;
import java.util.Comparator;

/** Queue-key arithmetic and the order within one dispatcher's queue. Stateless and thread-safe. */
public final class Keys {

    /** Within one dispatcher: smaller key first, ties by arrival sequence. */
    public static final Comparator<Job> BY_KEY_THEN_SEQUENCE = (a, b) -> {
        int byKey = Long.compare(a.key(), b.key());
        return byKey != 0 ? byKey : Long.compare(a.sequence(), b.sequence());
    };

    private Keys() {
    }

    /** {@code a + b}, or {@link Long#MAX_VALUE} / {@link Long#MIN_VALUE} instead of wrapping. */
    public static long saturatedAdd(long a, long b) {
        long sum = a + b;
        if (((a ^ sum) & (b ^ sum)) < 0) {
            return a < 0 ? Long.MIN_VALUE : Long.MAX_VALUE;
        }
        return sum;
    }
}
