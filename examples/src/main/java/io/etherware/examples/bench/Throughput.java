package io.etherware.examples.bench;

import io.etherware.core.component.Component;
import io.etherware.core.component.ComponentContext;
import io.etherware.core.kernel.EtherwareNode;
import io.etherware.core.message.Contents;
import io.etherware.core.message.Criticality;
import io.etherware.core.message.Message;
import io.etherware.core.message.Profile;
import io.etherware.core.message.QoS;
import io.etherware.core.scheduler.FifoScheduler;
import io.etherware.core.scheduler.Scheduler;
import io.etherware.rt.scheduling.RealtimeScheduler;
import io.etherware.rt.scheduling.RealtimeSchedulerConfig;
import io.etherware.rt.scheduling.ThreadSchedulingRule;
import java.lang.management.ManagementFactory;
import java.util.List;
import java.util.Locale;
import java.util.concurrent.ArrayBlockingQueue;
import java.util.concurrent.CompletableFuture;
import java.util.concurrent.TimeUnit;
import java.util.function.Supplier;

/**
 * Section 3: messages per second from one component to another on one node, for both schedulers,
 * beside a bare {@link ArrayBlockingQueue} hand-off between two threads. The source keeps one
 * window of {@value #WINDOW} messages in flight and the sink acknowledges each window (from the
 * kernel's throughput harness); the bytes allocated per message on the source's dispatcher are
 * given too.
 *
 * <p>The real-time scheduler runs its structure (four dispatchers, Algorithm 1 placement, HIGH
 * messages on dispatcher 1) at ordinary OS priorities here: a saturating pipeline must not hold
 * a SCHED_FIFO thread busy for seconds on a shared machine. Runs on the caller's thread.
 */
final class Throughput {

    static final String SECTION = "3. throughput, 2 components";
    private static final int WINDOW = 1_000;
    private static final Profile SOURCE = Profile.of("bench-source");
    private static final Profile SINK = Profile.of("bench-sink");
    private static final QoS DATA_QOS = QoS.of(Criticality.HIGH);

    record Data(long value) implements Contents {
    }

    record Ack(long count) implements Contents {
    }

    private final BenchConfig config;

    Throughput(BenchConfig config) {
        this.config = config;
    }

    List<BenchRow> measure() throws Exception {
        Supplier<Scheduler> realtime = () -> new RealtimeScheduler(RealtimeSchedulerConfig.builder()
                .threadSchedulingRule(ThreadSchedulingRule.nonRealtime(4)).build());
        String aim = ">= 1 M msg/s";
        BenchRow fifo = pipeline("throughput.fifo", "FifoScheduler (original Etherware)", FifoScheduler::new);
        BenchRow rt = pipeline("throughput.rt", "RealtimeScheduler (Algorithm 1, ordinary priorities)", realtime);
        var rows = new java.util.ArrayList<>(List.of(fifo.judged(aim, fifo.value() >= 1e6),
                rt.judged(aim, rt.value() >= 1e6), handOff()));
        rows.addAll(new HotPathAllocation(config).measure());
        return rows;
    }

    private BenchRow pipeline(String id, String name, Supplier<Scheduler> scheduler) throws Exception {
        var finished = new CompletableFuture<long[]>();
        long warmupNs = config.warmupNs();
        long measureNs = config.throughputNs();
        try (var node = EtherwareNode.builder().nodeId("bench-throughput").scheduler(scheduler).build()) {
            node.add(SINK, () -> new Component() {
                private long received;

                @Override
                public void onMessage(Message message, ComponentContext context) {
                    if (++received % WINDOW == 0) {
                        context.send(SOURCE, new Ack(received), DATA_QOS);
                    }
                }
            });
            node.add(SOURCE, () -> new Component() {
                private final long startNs = System.nanoTime();
                private long measureFromNs = -1;
                private long sentAtMeasure;
                private long allocatedAtMeasure;
                private long sent;

                @Override
                public void onMessage(Message message, ComponentContext context) {
                    long nowNs = System.nanoTime();
                    if (measureFromNs < 0 && nowNs - startNs > warmupNs) {
                        measureFromNs = nowNs;
                        sentAtMeasure = sent;
                        allocatedAtMeasure = Allocation.currentThreadBytes();
                    }
                    if (measureFromNs > 0 && nowNs - measureFromNs > measureNs) {
                        finished.complete(new long[] {sent - sentAtMeasure, nowNs - measureFromNs,
                            Allocation.currentThreadBytes() - allocatedAtMeasure});
                        return;
                    }
                    for (int i = 0; i < WINDOW; i++) {
                        context.send(SINK, new Data(sent++), DATA_QOS);
                    }
                }
            });
            node.start();
            node.send(SOURCE, new Ack(0), DATA_QOS);
            long[] result = finished.get(warmupNs + measureNs + TimeUnit.SECONDS.toNanos(60), TimeUnit.NANOSECONDS);
            double perSecond = result[0] * 1e9 / result[1];
            return BenchRow.value(id, SECTION, name, "idle", perSecond, "msg/s", String.format(Locale.ROOT,
                    "%d messages in %.2f s; %.0f B allocated per message on the source's dispatcher", result[0],
                    result[1] / 1e9, (double) result[2] / Math.max(1, result[0])));
        }
    }

    /** The floor: one thread puts, another takes, through a queue of one window. */
    private BenchRow handOff() throws InterruptedException {
        var queue = new ArrayBlockingQueue<Long>(WINDOW);
        var consumed = new long[1];
        Thread consumer = Thread.ofPlatform().name("bench-handoff-take").start(() -> {
            try {
                for (long value = queue.take(); value >= 0; value = queue.take()) {
                    consumed[0]++;
                }
            } catch (InterruptedException e) {
                Thread.currentThread().interrupt();
            }
        });
        long endWarmupNs = System.nanoTime() + config.warmupNs();
        long value = 0;
        while (System.nanoTime() < endWarmupNs) {
            queue.put(value++);
        }
        long startNs = System.nanoTime();
        long sentAtStart = value;
        long endNs = startNs + config.throughputNs();
        while (System.nanoTime() < endNs) {
            for (int i = 0; i < WINDOW; i++) {
                queue.put(value++);
            }
        }
        long elapsedNs = System.nanoTime() - startNs;
        queue.put(-1L);
        consumer.join();
        long messages = value - sentAtStart;
        return BenchRow.value("throughput.queue", SECTION, "ArrayBlockingQueue hand-off (floor)", "idle",
                messages * 1e9 / elapsedNs, "msg/s", String.format(Locale.ROOT,
                        "%d messages in %.2f s, queue of %d, consumed %d", messages, elapsedNs / 1e9, WINDOW, consumed[0]));
    }

    /** Bytes allocated by a thread, from {@code com.sun.management.ThreadMXBean}. */
    static final class Allocation {
        private static final com.sun.management.ThreadMXBean THREADS =
                (com.sun.management.ThreadMXBean) ManagementFactory.getThreadMXBean();

        private Allocation() {
        }

        static long currentThreadBytes() {
            return THREADS.getCurrentThreadAllocatedBytes();
        }

        static long threadBytes(Thread thread) {
            return THREADS.getThreadAllocatedBytes(thread.threadId());
        }
    }
}
