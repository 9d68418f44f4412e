package io.etherware.examples.bench;

import io.etherware.core.component.Component;
import io.etherware.core.kernel.EtherwareNode;
import io.etherware.core.message.Contents;
import io.etherware.core.message.Criticality;
import io.etherware.core.message.Message;
import io.etherware.core.message.MessageId;
import io.etherware.core.message.Profile;
import io.etherware.core.message.QoS;
import io.etherware.rt.platform.ThreadPolicy;
import io.etherware.rt.scheduling.RealtimeScheduler;
import io.etherware.rt.scheduling.RealtimeSchedulerConfig;
import io.etherware.rt.scheduling.ThreadSchedulingRule;
import io.etherware.services.notifier.Notifier;
import io.etherware.services.notifier.NotifierConfig;
import io.etherware.services.notifier.Subscription;
import java.util.List;
import java.util.Locale;
import java.util.concurrent.TimeUnit;
import java.util.concurrent.atomic.AtomicLong;
import java.util.concurrent.atomic.AtomicReference;
import java.util.concurrent.locks.LockSupport;

/**
 * Section 3, bytes allocated on the hot path in steady state (issue 15's aim: 0), summed over every
 * thread the path runs on, per message:
 * <ul>
 *   <li>a local send of a message the sender reuses, through the kernel and the real-time
 *       scheduler to {@code onMessage} (the sender's thread plus the receiving dispatcher's);</li>
 *   <li>a Tick's release and delivery at 1 kHz (the Notifier's thread plus the dispatcher's).</li>
 * </ul>
 * From {@code com.sun.management.ThreadMXBean}; the receiving component does nothing. The
 * scheduler runs at ordinary priorities here, like the throughput rows.
 */
final class HotPathAllocation {

    private static final Profile SINK = Profile.of("bench-alloc-sink");
    private static final QoS HIGH = QoS.of(Criticality.HIGH);
    private static final int BATCH = 1_000;

    record Sample(long value) implements Contents {
    }

    private final BenchConfig config;

    HotPathAllocation(BenchConfig config) {
        this.config = config;
    }

    List<BenchRow> measure() throws Exception {
        return List.of(reusedMessage(), ticks());
    }

    private BenchRow reusedMessage() throws Exception {
        var received = new AtomicLong();
        var receiver = new AtomicReference<Thread>();
        try (var node = node("bench-alloc")) {
            node.add(SINK, () -> (Component) (message, context) -> {
                receiver.compareAndSet(null, Thread.currentThread());
                received.incrementAndGet();
            });
            node.start();
            var message = new Message(SINK, Profile.of("bench-alloc-source"), node.clock().epochNanos(), HIGH,
                    new Sample(42), new MessageId(node.nodeId(), 1), null);
            long warmupNs = Math.max(config.warmupNs(), TimeUnit.MILLISECONDS.toNanos(500));
            long sent = sendFor(node, message, warmupNs, 0, received);
            long senderBefore = Throughput.Allocation.currentThreadBytes();
            long receiverBefore = Throughput.Allocation.threadBytes(receiver.get());
            long measuredFrom = sent;
            sent = sendFor(node, message, config.throughputNs(), sent, received);
            long senderBytes = Throughput.Allocation.currentThreadBytes() - senderBefore;
            long receiverBytes = Throughput.Allocation.threadBytes(receiver.get()) - receiverBefore;
            long messages = sent - measuredFrom;
            double perMessage = (double) (senderBytes + receiverBytes) / messages;
            return BenchRow.value("alloc.local-send", Throughput.SECTION, "local send of a reused message to onMessage",
                    "idle", perMessage, "B/msg", String.format(Locale.ROOT,
                            "%d messages; sender %.1f B/msg, dispatcher %.1f B/msg", messages,
                            (double) senderBytes / messages, (double) receiverBytes / messages))
                    .judged("0 B per message", senderBytes + receiverBytes == 0);
        }
    }

    /** Sends {@code message} in batches for {@code durationNs}, each batch after the last was handled. */
    private static long sendFor(EtherwareNode node, Message message, long durationNs, long sent, AtomicLong received) {
        long endNs = System.nanoTime() + durationNs;
        while (System.nanoTime() < endNs) {
            for (int i = 0; i < BATCH; i++) {
                node.send(message);
            }
            sent += BATCH;
            while (received.get() < sent) {
                LockSupport.parkNanos(10_000);
            }
        }
        return sent;
    }

    private BenchRow ticks() throws Exception {
        var received = new AtomicLong();
        var receiver = new AtomicReference<Thread>();
        try (var node = node("bench-alloc-ticks")) {
            Notifier notifier = Notifier.install(node, NotifierConfig.defaults()
                    .withThreadPolicy(ThreadPolicy.NON_REALTIME).withThreadName("bench-alloc-notifier"));
            node.add(SINK, () -> (Component) (message, context) -> {
                receiver.compareAndSet(null, Thread.currentThread());
                received.incrementAndGet();
            });
            node.start();
            notifier.subscribe(Subscription.periodic("alloc", SINK, Criticality.HIGH, BenchConfig.PERIOD_NS));
            TimeUnit.NANOSECONDS.sleep(Math.max(config.warmupNs(), TimeUnit.MILLISECONDS.toNanos(500)));
            Thread notifierThread = Thread.getAllStackTraces().keySet().stream()
                    .filter(t -> t.getName().startsWith("bench-alloc-notifier@")).findFirst().orElseThrow();
            long receivedBefore = received.get();
            long notifierBefore = Throughput.Allocation.threadBytes(notifierThread);
            long receiverBefore = Throughput.Allocation.threadBytes(receiver.get());
            TimeUnit.NANOSECONDS.sleep(config.throughputNs());
            long notifierBytes = Throughput.Allocation.threadBytes(notifierThread) - notifierBefore;
            long receiverBytes = Throughput.Allocation.threadBytes(receiver.get()) - receiverBefore;
            long ticks = Math.max(1, received.get() - receivedBefore);
            notifier.unsubscribe("alloc");
            return BenchRow.value("alloc.tick", Throughput.SECTION, "a Tick's release and delivery (1 kHz)", "idle",
                    (double) (notifierBytes + receiverBytes) / ticks, "B/tick", String.format(Locale.ROOT,
                            "%d Ticks; Notifier %.1f B/tick, dispatcher %.1f B/tick", ticks,
                            (double) notifierBytes / ticks, (double) receiverBytes / ticks))
                    .judged("0 B per Tick", notifierBytes + receiverBytes == 0);
        }
    }

    private EtherwareNode node(String nodeId) {
        return EtherwareNode.builder().nodeId(nodeId).scheduler(() -> new RealtimeScheduler(
                RealtimeSchedulerConfig.builder().threadSchedulingRule(ThreadSchedulingRule.nonRealtime(4)).build()))
                .build();
    }
}
