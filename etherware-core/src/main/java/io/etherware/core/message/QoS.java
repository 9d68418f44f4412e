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

    public QoS {
        Objects.requireNonNull(criticality, "criticality");
        requireNotNegative("periodNs", periodNs);
        requireNotNegative("deadlineNs", deadlineNs);
        requireNotNegative("wcetNs", wcetNs);
    }

    /** A QoS of the given criticality with no timing information. */
    public static QoS of(Criticality criticality) {
        return criticality == Criticality.NONE ? NONE : new QoS(criticality, 0, 0, 0);
    }

    /** A periodic stream: period and implicit deadline equal to the period. */
    public static QoS periodic(Criticality criticality, long periodNs) {
        if (periodNs <= 0) {
            throw new IllegalArgumentException("periodNs=" + periodNs + " must be > 0 for a periodic QoS");
        }
        return new QoS(criticality, periodNs, periodNs, 0);
    }

    public QoS withDeadlineNs(long newDeadlineNs) {
        return new QoS(criticality, periodNs, newDeadlineNs, wcetNs);
    }

    public QoS withWcetNs(long newWcetNs) {
        return new QoS(criticality, periodNs, deadlineNs, newWcetNs);
    }

    public boolean hasPeriod() {
        return periodNs > 0;
    }

    public boolean hasDeadline() {
        return deadlineNs > 0;
    }

    public boolean hasWcet() {
        return wcetNs > 0;
    }

    private static void requireNotNegative(String field, long valueNs) {
        if (valueNs < 0) {
            throw new IllegalArgumentException(field + "=" + valueNs + " must not be negative (use 0 for 'not specified')");
        }
    }
}
