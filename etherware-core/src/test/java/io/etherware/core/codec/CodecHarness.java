package io.etherware.core.codec;

import io.etherware.core.codec.TestContents.Angles;
import io.etherware.core.message.ContentsTypes;
import io.etherware.core.message.Criticality;
import io.etherware.core.message.Message;
import io.etherware.core.message.MessageId;
import io.etherware.core.message.Profile;
import io.etherware.core.message.QoS;
import io.etherware.core.message.Tick;

import java.lang.reflect.Method;
import java.util.Arrays;
import java.util.function.Supplier;

/**
 * Encode and decode cost of {@link MessageCodec}, per message, as percentiles of single-call
 * times after a warm-up, plus heap bytes allocated per call. Not part of the test suite; run:
 *
 * <pre>
 * ./mvnw -q -pl etherware-core -am test-compile
 * ./mvnw -q -pl etherware-core dependency:build-classpath -Dmdep.outputFile=target/test-classpath.txt
 * java -cp etherware-core/target/classes:etherware-core/target/test-classes:$(cat etherware-core/target/test-classpath.txt) \
 *      io.etherware.core.codec.CodecHarness [measuredOps]
 * </pre>
 *
 * Single-call times include one {@code System.nanoTime()} pair (about 20-30 ns). On a loaded
 * machine, read p50; p99 shows the other tenants as much as the codec.
 */
public final class CodecHarness {

    private static final int DEFAULT_MEASURED_OPS = 200_000;
    private static final int WARMUP_ROUNDS = 3;

    /** Keeps results alive so the JIT cannot drop the calls. */
    private static volatile long sink;

    private CodecHarness() {
    }

    public static void main(String[] args) {
        int measuredOps = args.length > 0 ? Integer.parseInt(args[0]) : DEFAULT_MEASURED_OPS;
        var types = new ContentsTypes().register("angles", Angles.class);
        var codec = MessageCodec.builder().contentsTypes(types).build();

        Message tick = new Message(Profile.parse("controller[car=1]"), Profile.parse("notifier"),
                1_732_233_600_000_000_000L, QoS.periodic(Criticality.HIGH, 15_000_000),
                new Tick(8_123_456_789L, 42, 15_000_000), new MessageId("node1", 1042), null);
        Message angles = new Message(Profile.parse("controller[car=1]"), Profile.parse("dsp-proxy[car=1]"),
                1_732_233_600_015_000_000L, new QoS(Criticality.HIGH, 15_000_000, 12_000_000, 2_000_000),
                new Angles(1001, -2048, 513, 15_015_000), new MessageId("node1", 3), null);

        System.out.printf("MessageCodec harness: %d measured ops per row, JDK %s, %d CPUs%n", measuredOps,
                Runtime.version(), Runtime.getRuntime().availableProcessors());
        System.out.printf("%-8s %-7s %6s %9s %9s %9s %9s %10s%n", "message", "op", "bytes", "p50 ns", "p90 ns",
                "p99 ns", "mean ns", "alloc B/op");
        for (int round = 0; round < WARMUP_ROUNDS; round++) {
            run(codec, tick, measuredOps, false);
            run(codec, angles, measuredOps, false);
        }
        run(codec, tick, measuredOps, true);
        run(codec, angles, measuredOps, true);
        System.out.println("(sink " + (sink & 1) + ")");
    }

    private static void run(MessageCodec codec, Message message, int ops, boolean report) {
        byte[] document = codec.encode(message);
        if (!codec.decode(document).equals(message)) {
            throw new IllegalStateException("round trip failed for " + message);
        }
        String name = message.contents().getClass().getSimpleName().toLowerCase();
        measure(name, "encode", document.length, ops, report, () -> codec.encode(message));
        measure(name, "decode", document.length, ops, report, () -> codec.decode(document));
    }

    private static void measure(String name, String op, int bytes, int ops, boolean report, Supplier<Object> call) {
        long[] timesNs = new long[ops];
        for (int i = 0; i < ops; i++) {
            long startNs = System.nanoTime();
            Object result = call.get();
            timesNs[i] = System.nanoTime() - startNs;
            sink += result.hashCode();
        }
        int allocationOps = Math.min(ops, 20_000);
        long allocatedBefore = currentThreadAllocatedBytes();
        for (int i = 0; i < allocationOps; i++) {
            sink += call.get().hashCode();
        }
        long allocatedPerOp = (currentThreadAllocatedBytes() - allocatedBefore) / allocationOps;
        if (report) {
            long meanNs = Arrays.stream(timesNs).sum() / ops;
            Arrays.sort(timesNs);
            System.out.printf("%-8s %-7s %6d %9d %9d %9d %9d %10d%n", name, op, bytes, percentile(timesNs, 0.50),
                    percentile(timesNs, 0.90), percentile(timesNs, 0.99), meanNs, allocatedPerOp);
        }
    }

    /**
     * {@code com.sun.management.ThreadMXBean#getCurrentThreadAllocatedBytes}, looked up
     * reflectively: test sources compile inside module io.etherware.core, which does not read
     * java.management, and the harness runs on the class path where reflection reaches it.
     */
    private static long currentThreadAllocatedBytes() {
        try {
            Object threads = Class.forName("java.lang.management.ManagementFactory").getMethod("getThreadMXBean")
                    .invoke(null);
            Method allocated = Class.forName("com.sun.management.ThreadMXBean").getMethod("getCurrentThreadAllocatedBytes");
            return (long) allocated.invoke(threads);
        } catch (ReflectiveOperationException e) {
            throw new IllegalStateException("this JVM does not report per-thread allocation", e);
        }
    }

    private static long percentile(long[] sorted, double quantile) {
        return sorted[Math.min(sorted.length - 1, (int) Math.ceil(quantile * sorted.length) - 1)];
    }
}
