package io.etherware.services.network.internal;

import java.util.random.RandomGenerator;

/**
 * Reconnection delays: exponential from an initial delay to a bound, each lowered by a random
 * part of up to {@code jitter} of itself so that nodes that lost each other at the same moment do
 * not redial in lock step.
 *
 * <p>Not thread-safe: one dialer owns it.
 */
final class Backoff {

    private final long initialNs;
    private final long maxNs;
    private final double jitter;
    private final RandomGenerator random;
    private int failures;

    Backoff(long initialNs, long maxNs, double jitter, RandomGenerator random) {
        this.initialNs = initialNs;
        this.maxNs = maxNs;
        this.jitter = jitter;
        this.random = random;
    }

    /** The delay before the next attempt; each call doubles the next one, up to the bound. */
    long nextDelayNs() {
        int doublings = Math.min(failures, 62);
        failures++;
        long baseNs = doublings >= Long.numberOfLeadingZeros(initialNs) - 1 ? maxNs
                : Math.min(maxNs, initialNs << doublings);
        return baseNs - (long) (baseNs * jitter * random.nextDouble());
    }

    /** After a success: the next delay is the initial one again. */
    void reset() {
        failures = 0;
    }
}
