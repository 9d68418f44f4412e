package io.etherware.core.message;

import java.util.Objects;

/**
 * Quality of Service of one message delivery, exactly the fields of the paper's Fig. 3.
 *
 * <p>Durations are nanoseconds; {@code 0} means "not specified" (a period, deadline or WCET of
 * zero has no meaning, so it is free to mean absent). {@code deadlineNs} is relative to the
 * message's release.
 *
 * @param criticality how critical the delivery is; never null
 * @param periodNs    the period of the stream this message belongs to, or 0
 * @param deadlineNs  relative deadline, or 0 for none
 * @param wcetNs      worst-case execution time of the receiver's handling, or 0
 */
public record QoS(Criticality criticality, long periodNs, long deadlineNs, long wcetNs) {

    /** Best effort: no criticality, no timing. The default for messages built without QoS. */
    public static final QoS NONE = new QoS(Criticality.NONE, 0, 0, 0);

    /**
     * Checks the components.
     *
     * @throws IllegalArgumentException naming the field if a duration is negative
     */
    public QoS {
        Objects.requireNonNull(criticality, "criticality");
        requireNotNegative("periodNs", periodNs);
        requireNotNegative("deadlineNs", deadlineNs);
        requireNotNegative("wcetNs", wcetNs);
    }

    /**
     * A QoS of the given criticality with no timing information.
     *
     * @param criticality how critical the delivery is
     * @return the QoS; {@link #NONE} itself for {@link Criticality#NONE}
     */
    public static QoS of(Criticality criticality) {
        return criticality == Criticality.NONE ? NONE : new QoS(criticality, 0, 0, 0);
    }

    /**
     * A periodic stream: period and implicit deadline equal to the period, WCET unspecified.
     *
     * @param criticality how critical the stream is
     * @param periodNs    the period in nanoseconds; &gt; 0
     * @return the QoS
     * @throws IllegalArgumentException if {@code periodNs} is not positive
     */
    public static QoS periodic(Criticality criticality, long periodNs) {
        if (periodNs <= 0) {
            throw new IllegalArgumentException("periodNs=" + periodNs + " must be > 0 for a periodic QoS");
        }
        return new QoS(criticality, periodNs, periodNs, 0);
    }

    /**
     * {@return this QoS with another relative deadline}
     *
     * @param newDeadlineNs the deadline in nanoseconds after the release; 0 for none
     * @throws IllegalArgumentException if it is negative
     */
    public QoS withDeadlineNs(long newDeadlineNs) {
        return new QoS(criticality, periodNs, newDeadlineNs, wcetNs);
    }

    /**
     * {@return this QoS with another worst-case execution time}
     *
     * @param newWcetNs the receiver's worst-case handling time in nanoseconds; 0 for unspecified
     * @throws IllegalArgumentException if it is negative
     */
    public QoS withWcetNs(long newWcetNs) {
        return new QoS(criticality, periodNs, deadlineNs, newWcetNs);
    }

    /** {@return whether a period is specified (non-zero)} */
    public boolean hasPeriod() {
        return periodNs > 0;
    }

    /** {@return whether a deadline is specified (non-zero)} */
    public boolean hasDeadline() {
        return deadlineNs > 0;
    }

    /** {@return whether a worst-case execution time is specified (non-zero)} */
    public boolean hasWcet() {
        return wcetNs > 0;
    }

    private static void requireNotNegative(String field, long valueNs) {
        if (valueNs < 0) {
            throw new IllegalArgumentException(field + "=" + valueNs + " must not be negative (use 0 for 'not specified')");
        }
    }
}
