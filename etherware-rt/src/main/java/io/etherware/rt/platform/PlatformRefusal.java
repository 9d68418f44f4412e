package io.etherware.rt.platform;

import java.util.Objects;

/**
 * A platform feature the OS refused (or that this platform lacks): what was asked, the errno, and
 * how to get it. Immutable.
 *
 * @param feature   which feature: {@code thread priority}, {@code cpu affinity}, {@code memory lock}
 * @param requested what was asked, e.g. {@code SCHED_FIFO/80}
 * @param errno     the errno of the refusing call; 38 ({@code ENOSYS}) when the call could not be
 *                  made at all (not Linux, symbol missing)
 * @param errnoName the symbolic errno, e.g. {@code EPERM}
 * @param fix       what the operator can do about it, in one sentence
 */
public record PlatformRefusal(String feature, String requested, int errno, String errnoName, String fix) {

    /**
     * Checks that every text is present.
     *
     * @throws NullPointerException when {@code feature}, {@code requested}, {@code errnoName} or
     *                              {@code fix} is null
     */
    public PlatformRefusal {
        Objects.requireNonNull(feature, "feature");
        Objects.requireNonNull(requested, "requested");
        Objects.requireNonNull(errnoName, "errnoName");
        Objects.requireNonNull(fix, "fix");
    }

    /** {@code thread priority SCHED_FIFO/80 refused: EPERM (errno 1); fix: ...}. */
    @Override
    public String toString() {
        return feature + " " + requested + " refused: " + errnoName + " (errno " + errno + "); fix: " + fix;
    }
}
