package io.etherware.core.time;

import java.time.Instant;

/** {@link NodeClock} on {@link System#nanoTime()} and {@link Instant#now()}. */
enum SystemClock implements NodeClock {
    INSTANCE;

    @Override
    public long nanoTime() {
        return System.nanoTime();
    }

    @Override
    public long epochNanos() {
        Instant now = Instant.now();
        return now.getEpochSecond() * 1_000_000_000L + now.getNano();
    }
}
