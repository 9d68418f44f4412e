package io.etherware.core.time;

import java.time.Duration;
import java.util.Objects;

/**
 * The one conversion from the API's {@link Duration}s (what a person configures) to the
 * nanoseconds the hot path keeps (what a loop reads), with an error that names the setting.
 * Stateless and thread-safe.
 */
public final class Durations {

    private Durations() {
    }

    /**
     * {@code duration} in nanoseconds.
     *
     * @param field    the setting's name, for the error message
     * @param duration the value; negative values pass through for the caller's own range check
     * @return the nanoseconds
     * @throws NullPointerException     naming {@code field} if {@code duration} is null
     * @throws IllegalArgumentException naming {@code field} if it does not fit a {@code long} of
     *                                  nanoseconds (about 292 years)
     */
    public static long toNs(String field, Duration duration) {
        Objects.requireNonNull(duration, () -> field + "=null: give a Duration, e.g. Duration.ofMillis(15)");
        try {
            return duration.toNanos();
        } catch (ArithmeticException e) {
            throw new IllegalArgumentException(field + "=" + duration + " is too long to count in nanoseconds", e);
        }
    }
}
