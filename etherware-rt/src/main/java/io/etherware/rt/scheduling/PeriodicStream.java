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

    /** A stream with an implicit deadline (= period). */
    public static PeriodicStream of(Profile target, Criticality criticality, long periodNs, long wcetNs) {
        return new PeriodicStream(target, QoS.periodic(criticality, periodNs).withWcetNs(wcetNs));
    }

    /** {@code wcet / period}. */
    public double utilization() {
        return (double) qos.wcetNs() / qos.periodNs();
    }
}
