package io.etherware.core.kernel;

import io.etherware.core.component.Component;
import io.etherware.core.component.ComponentContext;
import io.etherware.core.message.Contents;
import io.etherware.core.message.Message;
import io.etherware.core.message.Profile;
import java.util.Arrays;
import java.util.concurrent.CompletableFuture;
import java.util.concurrent.TimeUnit;

/**
 * Messages per second through the kernel with the original FIFO dispatcher, and round-trip
 * percentiles. Not part of the test suite; run it as a main (see the report for the command).
 *
 * <ol>
 *   <li>Pipeline: a source component sends windows of {@value #WINDOW} messages to a sink, which
 *       acknowledges each window; both share the one FIFO dispatcher. Also the bytes allocated per
 *       message on the dispatcher thread.</li>
 *   <li>Ping-pong: one message at a time between two components; round trip from the ping's send
 *       to the pong's reply being handled, on the same dispatcher.</li>
 *   <li>Outside request: a main thread's blocking request to an echo component and back (two
 *       thread hand-offs with wake-ups).</li>
 * </ol>
 * Each phase is warmed up first; durations are short because the machine is shared.
 */
public final class KernelThroughputHarness {

    private static final int WINDOW = 1_000;
    private static final long WARMUP_NS = TimeUnit.SECONDS.toNanos(2);
    private static final long MEASURE_NS = TimeUnit.SECONDS.toNanos(3);

    record Data(long value) implements Contents {}

    record Ack(long count) implements Contents {}

    record Ping(long sentNs) implements Contents {}

    private static final Profile SOURCE = Profile.of("source");
    private static final Profile SINK = Profile.of("sink");

    public static void main(String[] args) throws Exception {
        System.out.printf("JDK %s, %d CPUs, scheduler fifo%n", Runtime.version(), Runtime.getRuntime().availableProcessors());
        pipeline();
        pingPong();
        outsideRequests();
    }

    /** The source keeps one window in flight; the sink acknowledges every window. */
    private static void pipeline() throws Exception {
        var finished = new CompletableFuture<long[]>();
        try (var node = EtherwareNode.builder().nodeId("bench").build()) {
            node.add(SINK, () -> new Component() {
                private long received;

                @Override
                public void onMessage(Message message, ComponentContext context) {
                    if (++received % WINDOW == 0) {
                        context.send(SOURCE, new Ack(received));
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
                public void onStart(ComponentContext context) {
                }

                @Override
                public void onMessage(Message message, ComponentContext context) {
                    long nowNs = System.nanoTime();
                    if (measureFromNs < 0 && nowNs - startNs > WARMUP_NS) {
                        measureFromNs = nowNs;
                        sentAtMeasure = sent;
                        allocatedAtMeasure = allocatedBytes();
                    }
                    if (measureFromNs > 0 && nowNs - measureFromNs > MEASURE_NS) {
                        finished.complete(new long[] {sent - sentAtMeasure, nowNs - measureFromNs,
                                allocatedBytes() - allocatedAtMeasure});
                        return;
                    }
                    for (int i = 0; i < WINDOW; i++) {
                        context.send(SINK, new Data(sent++));
                    }
                }
            });
            node.start();
            node.send(SOURCE, new Ack(0));
            long[] result = finished.get(60, TimeUnit.SECONDS);
            double perSecond = result[0] * 1e9 / result[1];
            System.out.printf("pipeline source->sink, 1 FIFO dispatcher: %,.0f messages/s (%,d messages in %.2f s),"
                    + " %.0f bytes allocated per message on the dispatcher%n",
                    perSecond, result[0], result[1] / 1e9, (double) result[2] / result[0]);
        }
    }

    /**
     * Bytes allocated so far by the calling thread. Through reflection: the test sources are
     * compiled into the core module, which does not read java.management (the harness runs on
     * the class path, where it is readable).
     */
    private static long allocatedBytes() {
        try {
            Object threads = Class.forName("java.lang.management.ManagementFactory").getMethod("getThreadMXBean")
                    .invoke(null);
            return (long) Class.forName("com.sun.management.ThreadMXBean").getMethod("getCurrentThreadAllocatedBytes")
                    .invoke(threads);
        } catch (ReflectiveOperationException e) {
            throw new IllegalStateException("allocation counter unavailable", e);
        }
    }

    /** One message in flight; every round trip is recorded after the warm-up. */
    private static void pingPong() throws Exception {
        int capacity = 5_000_000;
        long[] roundTripsNs = new long[capacity];
        var finished = new CompletableFuture<Integer>();
        try (var node = EtherwareNode.builder().nodeId("pingpong").build()) {
            node.add(SINK, () -> (message, context) -> context.reply(message, message.contents()));
            node.add(SOURCE, () -> new Component() {
                private final long startNs = System.nanoTime();
                private long measureFromNs = -1;
                private int count;

                @Override
                public void onMessage(Message message, ComponentContext context) {
                    long nowNs = System.nanoTime();
                    if (message.contents() instanceof Ping ping) {
                        if (measureFromNs > 0 && count < capacity) {
                            roundTripsNs[count++] = nowNs - ping.sentNs();
                        } else if (measureFromNs < 0 && nowNs - startNs > WARMUP_NS) {
                            measureFromNs = nowNs;
                        }
                        if (measureFromNs > 0 && (nowNs - measureFromNs > MEASURE_NS || count == capacity)) {
                            finished.complete(count);
                            return;
                        }
                    }
                    context.send(SINK, new Ping(System.nanoTime()));
                }
            });
            node.start();
            node.send(SOURCE, new Ack(0));
            int count = finished.get(60, TimeUnit.SECONDS);
            printPercentiles("ping-pong round trip, both on the FIFO dispatcher", roundTripsNs, count,
                    sumNs(roundTripsNs, count));
        }
    }

    private static void outsideRequests() {
        try (var node = EtherwareNode.builder().nodeId("outside").build()) {
            node.add(SINK, () -> (message, context) -> context.reply(message, message.contents()));
            node.start();
            long warmupEndNs = System.nanoTime() + WARMUP_NS;
            while (System.nanoTime() < warmupEndNs) {
                node.requestBlocking(SINK, new Ack(0));
            }
            long[] roundTripsNs = new long[2_000_000];
            int count = 0;
            long endNs = System.nanoTime() + MEASURE_NS;
            while (count < roundTripsNs.length) {
                long startNs = System.nanoTime();
                if (startNs > endNs) {
                    break;
                }
                node.requestBlocking(SINK, new Ack(count));
                roundTripsNs[count++] = System.nanoTime() - startNs;
            }
            printPercentiles("outside requestBlocking round trip (main thread <-> dispatcher)", roundTripsNs, count,
                    sumNs(roundTripsNs, count));
        }
    }

    private static long sumNs(long[] samplesNs, int count) {
        long sum = 0;
        for (int i = 0; i < count; i++) {
            sum += samplesNs[i];
        }
        return sum;
    }

    /** Round trips are back to back, so their sum is the busy time they measure. */
    private static void printPercentiles(String what, long[] samplesNs, int count, long busyNs) {
        long[] sorted = Arrays.copyOf(samplesNs, count);
        Arrays.sort(sorted);
        System.out.printf("%s: n=%,d p50=%.2f us p99=%.2f us p99.9=%.2f us max=%.2f us (%,.0f round trips/s)%n", what,
                count, percentile(sorted, 0.50) / 1e3, percentile(sorted, 0.99) / 1e3, percentile(sorted, 0.999) / 1e3,
                sorted[count - 1] / 1e3, count * 1e9 / busyNs);
    }

    private static long percentile(long[] sorted, double fraction) {
        return sorted[Math.min(sorted.length - 1, (int) Math.ceil(fraction * sorted.length) - 1)];
    }
}
