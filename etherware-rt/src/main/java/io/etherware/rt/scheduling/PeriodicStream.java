package io.etherware.rt.scheduling;

import io.etherware.core.message.Criticality;
import io.etherware.core.message.Profile;
import io.etherware.core.message.QoS;
import java.util.Objects;

/**
 * A periodic stream of messages declared to admission control: every {@code periodNs} a message
 * of this QoS goes to {@code target}, whose handling takes at most {@code wcetNs}. Immutable.
 *
 * @param target the receiving component
 * @param qos    the messages' QoS; must have a period and a WCET, and WCET must not exceed the
 *               deadline (or the period when there is no deadline)
 */
public record PeriodicStream(Profile target, QoS qos) {

    /**
     * Checks that admission control can use the stream.
     *
     * @throws NullPointerException     when {@code target} or {@code qos} is null
     * @throws IllegalArgumentException when {@code qos} has no period or no WCET, or its WCET exceeds
     *                                  its deadline (its period when it has no deadline)
     */
    public PeriodicStream {
        Objects.requireNonNull(target, "target");
        Objects.requireNonNull(qos, "qos");
        if (!qos.hasPeriod()) {
            throw new IllegalArgumentException("stream to " + target + ": qos.periodNs=0, a periodic stream needs a period");
        }
        if (!qos.hasWcet()) {
            throw new IllegalArgumentException("stream to " + target + ": qos.wcetNs=0, admission control needs a WCET");
        }
        long limitNs = qos.hasDeadline() ? qos.deadlineNs() : qos.periodNs();
        if (qos.wcetNs() > limitNs) {
            throw new IllegalArgumentException("stream to " + target + ": qos.wcetNs=" + qos.wcetNs()
                    + " exceeds its " + (qos.hasDeadline() ? "deadlineNs=" : "periodNs=") + limitNs);
        }
    }

    /**
     * A stream with an implicit deadline (= period).
     *
     * @param target      the receiving component
     * @param criticality the messages' criticality
     * @param periodNs    the period in nanoseconds, greater than 0
     * @param wcetNs      the worst-case execution time of one message's handling in nanoseconds,
     *                    in 1..{@code periodNs}
     * @return the stream
     * @throws IllegalArgumentException when {@code periodNs} or {@code wcetNs} is out of range
     */
    public static PeriodicStream of(Profile target, Criticality criticality, long periodNs, long wcetNs) {
        return new PeriodicStream(target, QoS.periodic(criticality, periodNs).withWcetNs(wcetNs));
    }

    /**
     * The share of one CPU the stream needs.
     *
     * @return {@code wcet / period}, greater than 0; at most 1 unless the deadline is longer than
     *         the period
     */
    public double utilization() {
        return (double) qos.wcetNs() / qos.periodNs();
    }
}
