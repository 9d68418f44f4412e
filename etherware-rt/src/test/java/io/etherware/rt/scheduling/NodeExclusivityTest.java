package io.etherware.rt.scheduling;

import static org.junit.jupiter.api.Assertions.assertEquals;
import static org.junit.jupiter.api.Assertions.assertTrue;

import io.etherware.core.kernel.EtherwareNode;
import io.etherware.core.message.Contents;
import io.etherware.core.message.Criticality;
import io.etherware.core.message.Profile;
import io.etherware.core.message.QoS;
import java.util.ArrayList;
import java.util.List;
import java.util.concurrent.TimeUnit;
import java.util.concurrent.atomic.AtomicBoolean;
import java.util.concurrent.atomic.AtomicLong;
import org.junit.jupiter.api.Test;

/**
 * Design decision 3 through the real {@link RealtimeScheduler}: one component flooded at once with
 * messages of every criticality, which Algorithm 1 places on all four dispatchers, so jobs for it
 * are parked with the component and handed on between dispatchers all the time. It never handles
 * two messages at once, loses none, and keeps each sender's messages in order (one sender sends at
 * one criticality and period, so its jobs have non-decreasing keys on one dispatcher).
 */
class NodeExclusivityTest {

    private static final Profile SINK = Profile.of("sink");
    private static final int PER_SENDER = 20_000;
    private static final List<QoS> STREAMS = List.of(QoS.NONE,
            QoS.periodic(Criticality.LOW, TimeUnit.MILLISECONDS.toNanos(5)),
            QoS.periodic(Criticality.MIDDLE, TimeUnit.MILLISECONDS.toNanos(5)),
            QoS.periodic(Criticality.HIGH, TimeUnit.MILLISECONDS.toNanos(5)));

    record Seq(int stream, long value) implements Contents {
    }

    @Test
    void shouldNeverOverlapLoseOrReorderWhenOneComponentGetsEveryCriticalityAtOnce() throws Exception {
        var inside = new AtomicBoolean();
        var overlaps = new AtomicLong();
        var outOfOrder = new AtomicLong();
        long[] next = new long[STREAMS.size()]; // unsynchronized on purpose: exclusivity makes it safe
        var scheduler = RealtimeScheduler.withDefaults();
        try (var node = EtherwareNode.builder().nodeId("exclusive-rt").scheduler(() -> scheduler).build()) {
            node.add(SINK, () -> (message, context) -> {
                if (!inside.compareAndSet(false, true)) {
                    overlaps.incrementAndGet();
                }
                Thread.onSpinWait(); // a little work, so that dispatchers meet at the component
                Seq seq = message.contentsAs(Seq.class);
                if (seq.value() != next[seq.stream()]) {
                    outOfOrder.incrementAndGet();
                }
                next[seq.stream()] = seq.value() + 1;
                inside.set(false);
            });
            node.start();

            List<Thread> senders = new ArrayList<>();
            for (int stream = 0; stream < STREAMS.size(); stream++) {
                int s = stream;
                senders.add(Thread.ofPlatform().name("sender-" + s).start(() -> {
                    for (long i = 0; i < PER_SENDER; i++) {
                        node.send(SINK, new Seq(s, i), STREAMS.get(s));
                    }
                }));
            }
            for (Thread sender : senders) {
                sender.join();
            }
            long expected = (long) STREAMS.size() * PER_SENDER;
            long deadlineNs = System.nanoTime() + TimeUnit.SECONDS.toNanos(30);
            while (node.shell(SINK).handledCount() < expected && System.nanoTime() < deadlineNs) {
                Thread.sleep(10);
            }
            assertEquals(expected, node.shell(SINK).handledCount(), "messages handled");
        }

        assertEquals(0, overlaps.get(), "overlapping onMessage calls on one component");
        assertEquals(0, outOfOrder.get(), "messages of one sender out of order");
        for (int stream = 0; stream < STREAMS.size(); stream++) {
            assertEquals(PER_SENDER, next[stream], "messages of stream " + STREAMS.get(stream));
        }
        long dispatchersUsed = scheduler.stats().dispatchers().stream().filter(d -> d.jobsRun() > 0).count();
        assertTrue(dispatchersUsed == 4, "jobs ran on " + dispatchersUsed + " dispatchers, not all four");
        long parked = scheduler.stats().dispatchers().stream().mapToLong(d -> d.jobsParked()).sum();
        assertTrue(parked > 0, "no job was parked with the busy component: the hand-over path was not exercised");
    }
}
