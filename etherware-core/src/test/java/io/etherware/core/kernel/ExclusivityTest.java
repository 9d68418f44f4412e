package io.etherware.core.kernel;

import static org.junit.jupiter.api.Assertions.assertEquals;
import static org.junit.jupiter.api.Assertions.assertTrue;

import io.etherware.core.component.Component;
import io.etherware.core.component.ComponentContext;
import io.etherware.core.message.Message;
import io.etherware.core.message.Profile;
import io.etherware.core.scheduler.FifoScheduler;
import io.etherware.core.scheduler.Scheduler;
import io.etherware.core.testing.Await;
import io.etherware.core.testing.MultiDispatcherScheduler;
import io.etherware.core.testing.Num;
import java.util.ArrayList;
import java.util.List;
import java.util.concurrent.ConcurrentHashMap;
import java.util.concurrent.atomic.AtomicBoolean;
import java.util.concurrent.atomic.AtomicLong;
import java.util.function.Supplier;
import org.junit.jupiter.api.Test;

/** Design decision 3: one message at a time per component, whatever the dispatchers. */
class ExclusivityTest {

    private static final Profile SINK = Profile.of("sink");
    private static final int SENDERS = 4;
    private static final int PER_SENDER = 25_000;

    /** Counts overlapping handlings with an atomic flag, and messages per source in order. */
    private static final class Sink implements Component {
        final AtomicBoolean inside = new AtomicBoolean();
        final AtomicLong overlaps = new AtomicLong();
        final AtomicLong received = new AtomicLong();
        final AtomicLong outOfOrder = new AtomicLong();
        final ConcurrentHashMap<String, Long> lastBySource = new ConcurrentHashMap<>();

        @Override
        public void onMessage(Message message, ComponentContext context) {
            if (!inside.compareAndSet(false, true)) {
                overlaps.incrementAndGet();
            }
            // A little work, so that dispatchers really meet at the gate.
            Thread.onSpinWait();
            String source = String.valueOf(message.sender());
            long value = message.contentsAs(Num.class).value();
            Long last = lastBySource.put(source, value);
            if (last != null && value != last + 1) {
                outOfOrder.incrementAndGet();
            }
            received.incrementAndGet();
            inside.set(false);
        }
    }

    /** A component that floods the sink from its own thread, so senders run in parallel. */
    private static Component flooder() {
        return new Component() {
            @Override
            public void onStart(ComponentContext context) {
                Thread.ofPlatform().name("flooder-" + context.self()).start(() -> {
                    for (long i = 0; i < PER_SENDER; i++) {
                        context.send(SINK, new Num(i));
                    }
                });
            }

            @Override
            public void onMessage(Message message, ComponentContext context) {
            }
        };
    }

    private static Sink flood(Supplier<Scheduler> scheduler, String nodeId) {
        var sink = new Sink();
        try (var node = EtherwareNode.builder().nodeId(nodeId).scheduler(scheduler).build()) {
            node.add(SINK, () -> sink);
            for (int i = 0; i < SENDERS; i++) {
                node.add(Profile.of("source", "n", Integer.toString(i)), ExclusivityTest::flooder);
            }
            node.start();
            Await.until("all flood messages counted", () -> node.shell(SINK).handledCount() == (long) SENDERS * PER_SENDER);
        }
        return sink;
    }

    @Test
    void shouldNeverOverlapNorLoseWhenFloodedFromSeveralThreadsOnTheFifoScheduler() {
        Sink sink = flood(FifoScheduler::new, "flood-fifo");
        assertEquals(0, sink.overlaps.get(), "overlapping onMessage calls");
        assertEquals((long) SENDERS * PER_SENDER, sink.received.get());
        assertEquals(0, sink.outOfOrder.get(), "per-source order");
    }

    @Test
    void shouldNeverOverlapNorLoseWhenJobsForOneComponentSpreadOverFourDispatchers() {
        Sink sink = flood(() -> MultiDispatcherScheduler.roundRobin(4), "flood-rr");
        assertEquals(0, sink.overlaps.get(), "overlapping onMessage calls");
        assertEquals((long) SENDERS * PER_SENDER, sink.received.get());
    }

    @Test
    void shouldKeepPerSourceOrderWhenSourcesArePlacedOnDifferentDispatchers() {
        Sink sink = flood(() -> MultiDispatcherScheduler.bySender(3), "flood-by-sender");
        assertEquals(0, sink.overlaps.get(), "overlapping onMessage calls");
        assertEquals(0, sink.outOfOrder.get(), "messages of one source out of order");
        assertEquals(SENDERS, sink.lastBySource.size());
        for (long last : sink.lastBySource.values()) {
            assertEquals(PER_SENDER - 1, last);
        }
    }

    @Test
    void shouldRunParkedJobsAfterTheBusyHandlingWhenDispatchersCompete() {
        // Round robin over 3 dispatchers from one source: the order across dispatchers is not
        // promised, but every message must arrive exactly once.
        var seen = ConcurrentHashMap.<Long>newKeySet();
        var duplicates = new AtomicLong();
        var order = new ArrayList<Long>();
        try (var node = EtherwareNode.builder().nodeId("rr-once")
                .scheduler(() -> MultiDispatcherScheduler.roundRobin(3)).build()) {
            node.add(SINK, () -> (message, context) -> {
                long value = message.contentsAs(Num.class).value();
                if (!seen.add(value)) {
                    duplicates.incrementAndGet();
                }
                order.add(value); // unsynchronized on purpose: exclusivity makes it safe
            });
            node.start();
            for (long i = 0; i < 50_000; i++) {
                node.send(SINK, new Num(i));
            }
            Await.until("all messages", () -> node.shell(SINK).handledCount() == 50_000);
        }
        assertEquals(0, duplicates.get());
        assertEquals(50_000, seen.size());
        assertEquals(50_000, order.size());
        List<Long> sorted = new ArrayList<>(order);
        sorted.sort(null);
        assertTrue(sorted.getFirst() == 0 && sorted.getLast() == 49_999);
    }
}
