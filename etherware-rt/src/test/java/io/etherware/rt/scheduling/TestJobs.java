package io.etherware.rt.scheduling;

import io.etherware.core.message.Criticality;
import io.etherware.core.message.Empty;
import io.etherware.core.message.Message;
import io.etherware.core.message.MessageId;
import io.etherware.core.message.Profile;
import io.etherware.core.message.QoS;
import io.etherware.core.scheduler.Job;
import java.util.concurrent.atomic.AtomicLong;

/** Jobs as the kernel makes them: a message, the target's name, an opaque target, a sequence. */
final class TestJobs {

    private static final AtomicLong SEQUENCE = new AtomicLong();

    private TestJobs() {
    }

    /** A job for {@code target}; the target object is the name itself (identity is what counts). */
    static Job job(String target, QoS qos, long releaseNs) {
        long sequence = SEQUENCE.incrementAndGet();
        var message = new Message(Profile.of(target), null, 0L, qos, Empty.INSTANCE, new MessageId("test", sequence),
                null);
        return new Job(message, target, target, sequence, releaseNs);
    }

    static Job job(String target, Criticality criticality, long periodNs, long releaseNs) {
        QoS qos = periodNs > 0 ? QoS.periodic(criticality, periodNs) : QoS.of(criticality);
        return job(target, qos, releaseNs);
    }
}
