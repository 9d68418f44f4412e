package io.etherware.core.message;

/**
 * How much a message matters for timeliness (paper Fig. 3).
 *
 * <p>{@link #NONE} marks a message without real-time requirements: the original Etherware's
 * best-effort delivery. The others are ordered from least to most critical, so
 * {@code HIGH.compareTo(LOW) > 0}.
 */
public enum Criticality {
    /** No real-time requirement; delivered by the non-real-time dispatcher. */
    NONE,
    /** Real-time, least critical; a real-time scheduler serves it after the others. */
    LOW,
    /** Real-time, between {@link #LOW} and {@link #HIGH}. */
    MIDDLE,
    /** Real-time, most critical, e.g. a control loop; a real-time scheduler serves it first. */
    HIGH
}
