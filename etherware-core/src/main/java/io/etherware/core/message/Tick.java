package io.etherware.core.message;

/**
 * A time-driven activation from the Notifier (paper Section III-C), registered as {@code tick}.
 *
 * @param releaseNs the scheduled release time on the sending node's monotonic clock
 *                  ({@code System.nanoTime()} base), so a receiver can measure its lateness
 * @param sequence  the index k of this release in {@code t0 + k * periodNs}
 * @param periodNs  the subscription's period, or 0 for a one-shot tick
 */
public record Tick(long releaseNs, long sequence, long periodNs) implements Contents {
    /**
     * Checks the components.
     *
     * @throws IllegalArgumentException if {@code sequence} or {@code periodNs} is negative
     */
    public Tick {
        if (sequence < 0) {
            throw new IllegalArgumentException("sequence=" + sequence + " must be >= 0");
        }
        if (periodNs < 0) {
            throw new IllegalArgumentException("periodNs=" + periodNs + " must not be negative");
        }
    }
}
