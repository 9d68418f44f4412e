package io.etherware.services.network.internal;

import static org.junit.jupiter.api.Assertions.assertEquals;
import static org.junit.jupiter.api.Assertions.assertTrue;

import java.util.SplittableRandom;
import java.util.concurrent.TimeUnit;
import org.junit.jupiter.api.Test;

class BackoffTest {

    private static final long MS = TimeUnit.MILLISECONDS.toNanos(1);

    @Test
    void shouldDoubleUpToTheBoundAndStartOverAfterAReset() {
        var backoff = new Backoff(50 * MS, 1_000 * MS, 0, new SplittableRandom(1));
        assertEquals(50 * MS, backoff.nextDelayNs());
        assertEquals(100 * MS, backoff.nextDelayNs());
        assertEquals(200 * MS, backoff.nextDelayNs());
        assertEquals(400 * MS, backoff.nextDelayNs());
        assertEquals(800 * MS, backoff.nextDelayNs());
        assertEquals(1_000 * MS, backoff.nextDelayNs());
        for (int i = 0; i < 100; i++) {
            assertEquals(1_000 * MS, backoff.nextDelayNs(), "no overflow after many failures");
        }
        backoff.reset();
        assertEquals(50 * MS, backoff.nextDelayNs());
    }

    @Test
    void shouldLowerEachDelayByAtMostTheJitterAndSpreadThem() {
        var backoff = new Backoff(100 * MS, 100 * MS, 0.2, new SplittableRandom(7));
        long min = Long.MAX_VALUE;
        long max = Long.MIN_VALUE;
        for (int i = 0; i < 1_000; i++) {
            long delay = backoff.nextDelayNs();
            min = Math.min(min, delay);
            max = Math.max(max, delay);
        }
        assertTrue(min >= 80 * MS && max <= 100 * MS, min + ".." + max);
        assertTrue(max - min > 15 * MS, "delays are spread, not in lock step: " + min + ".." + max);
    }
}
