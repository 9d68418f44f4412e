package io.etherware.services.management;

import example.counter.Chain;
import example.counter.ChainCounter;
import example.counter.ChainCounterV2;
import example.counter.Seq;
import io.etherware.core.kernel.EtherwareNode;
import io.etherware.core.message.Criticality;
import io.etherware.core.message.Profile;
import io.etherware.core.message.QoS;
import io.etherware.core.scheduler.FifoScheduler;
import io.etherware.core.scheduler.Scheduler;
import io.etherware.rt.scheduling.RealtimeScheduler;
import io.etherware.rt.scheduling.RealtimeSchedulerConfig;
import io.etherware.rt.scheduling.ThreadSchedulingRule;
import java.nio.file.Files;
import java.nio.file.Path;
import java.util.Arrays;
import java.util.Locale;
import java.util.Map;
import java.util.concurrent.TimeUnit;
import java.util.function.Supplier;

/**
 * The upgrade gap, measured: a component keeps one message in flight to itself (so a message is
 * always waiting when the swap happens) and is upgraded through the management service again and
 * again; prints percentiles of the gap, the pause, the load and the whole request. Not part of
 * the test suite; run it as a main:
 *
 * <pre>
 * ./mvnw -q -pl etherware-services -am test-compile dependency:build-classpath \
 *     -Dmdep.outputFile=/tmp/upgrade-cp.txt -Dmdep.includeScope=test
 * java --enable-native-access=ALL-UNNAMED \
 *     -cp etherware-services/target/test-classes:etherware-services/target/classes:$(cat /tmp/upgrade-cp.txt) \
 *     io.etherware.services.management.UpgradeGapHarness [fifo|rt|rt-fifo] [classpath|jar] [repetitions]
 * </pre>
 *
 * {@code classpath} alternates between two warmed-up classes on the class path; {@code jar} loads
 * a fresh copy of the new logic from a jar every time (new class loader, so the code that runs in
 * the pause has never run before). {@code rt} is the real-time scheduler's structure (Algorithm 1,
 * four dispatchers) at ordinary OS priorities; {@code rt-fifo} the same with the paper's Table II
 * (SCHED_FIFO 80/70/60, needs the privilege). The chain runs only from just before the request to
 * its answer (well under a millisecond), so even at a real-time priority it occupies a core only in
 * short bursts.
 */
public final class UpgradeGapHarness {

    private static final Profile LOOP = Profile.parse("loop[harness=gap]");
    private static final QoS LOOP_QOS = QoS.of(Criticality.MIDDLE);
    private static final int WARMUP = 50;

    private UpgradeGapHarness() {
    }

    public static void main(String[] args) throws Exception {
        String schedulerName = args.length > 0 ? args[0] : "fifo";
        String source = args.length > 1 ? args[1] : "classpath";
        int repetitions = args.length > 2 ? Integer.parseInt(args[2]) : 200;
        Supplier<Scheduler> scheduler = switch (schedulerName) {
            case "fifo" -> FifoScheduler::new;
            case "rt" -> () -> new RealtimeScheduler(RealtimeSchedulerConfig.builder()
                    .threadSchedulingRule(ThreadSchedulingRule.nonRealtime(4)).build());
            case "rt-fifo" -> () -> new RealtimeScheduler(RealtimeSchedulerConfig.builder()
                    .threadSchedulingRule(ThreadSchedulingRule.tableII()).build());
            default -> throw new IllegalArgumentException("scheduler '" + schedulerName + "': use fifo, rt or rt-fifo");
        };
        Path directory = Files.createTempDirectory("etherware-gap-harness");
        Implementation[] implementations = switch (source) {
            case "classpath" -> new Implementation[] {
                Implementation.ofClass(ChainCounterV2.class), Implementation.ofClass(ChainCounter.class)};
            case "jar" -> new Implementation[] {
                Implementation.fromJar(jarOfFreshLogic(directory), "fresh.ChainCounterV3")};
            default -> throw new IllegalArgumentException("source '" + source + "': use classpath or jar");
        };

        long[] gapNs = new long[repetitions];
        long[] pauseNs = new long[repetitions];
        long[] loadNs = new long[repetitions];
        long[] totalNs = new long[repetitions];
        int unmeasured = 0;
        try (var node = EtherwareNode.builder().nodeId("gap").scheduler(scheduler).build()) {
            ManagementService.install(node, ManagementConfig.builder().allowDirectory(directory).build());
            node.add(LOOP, ChainCounter::new);
            node.start();
            for (int i = -WARMUP; i < repetitions; i++) {
                UpgradeResult result = upgradeWhileChained(node, implementations[Math.floorMod(i, implementations.length)]);
                if (i < 0) {
                    continue;
                }
                if (result.gapNs() < 0) {
                    unmeasured++;
                }
                gapNs[i] = result.gapNs();
                pauseNs[i] = result.pauseNs();
                loadNs[i] = result.loadNs();
                totalNs[i] = result.totalNs();
            }
        }
        System.out.printf(Locale.ROOT, "upgrade gap harness: scheduler=%s source=%s repetitions=%d (after %d warm-up)"
                + " breaks-in-sequence=%d gap-unmeasured=%d cpus=%d%n", schedulerName, source, repetitions, WARMUP,
                Chain.breaks.get(), unmeasured, Runtime.getRuntime().availableProcessors());
        if (!Chain.firstBreaks.isEmpty()) {
            System.out.println("  first breaks (expected->got): " + Chain.firstBreaks);
        }
        print("gap   (old logic's last message end -> new logic's first start)", gapNs);
        print("pause (swap at the message boundary)", pauseNs);
        print("load  (class, checks, constructor; off the dispatchers)", loadNs);
        print("total (request at the service -> end of the pause)", totalNs);
    }

    private static UpgradeResult upgradeWhileChained(EtherwareNode node, Implementation implementation)
            throws Exception {
        Chain.ended = false;
        Chain.running = true;
        node.send(LOOP, new Seq(Chain.lastSequence + 1), LOOP_QOS);
        UpgradeResult result = Management.upgrade(node, node.nodeId(), LOOP, implementation).get(30, TimeUnit.SECONDS);
        Chain.running = false;
        while (!Chain.ended) { // the message in flight lands and sends nothing more
            TimeUnit.MILLISECONDS.sleep(1);
        }
        return result;
    }

    private static Path jarOfFreshLogic(Path directory) throws Exception {
        return JarBuilder.build(directory.resolve("chain-v3.jar"), Map.of("fresh.ChainCounterV3", """
                package fresh;

                import example.counter.Chain;
                import example.counter.CounterState;
                import example.counter.Seq;
                import io.etherware.core.component.Component;
                import io.etherware.core.component.ComponentContext;
                import io.etherware.core.component.ComponentState;
                import io.etherware.core.message.Message;

                public class ChainCounterV3 implements Component {
                    private long count;
                    private long lastSequence = -1;

                    @Override
                    public void onMessage(Message message, ComponentContext context) {
                        if (!(message.contents() instanceof Seq seq)) {
                            return;
                        }
                        if (lastSequence >= 0 && seq.value() != lastSequence + 1) {
                            Chain.broken(lastSequence, seq.value());
                        }
                        lastSequence = seq.value();
                        count++;
                        Chain.lastSequence = lastSequence;
                        if (Chain.running) {
                            context.send(context.self(), new Seq(lastSequence + 1), message.qos());
                        } else {
                            Chain.ended = true;
                        }
                    }

                    @Override
                    public ComponentState snapshot() {
                        return new CounterState(count, lastSequence);
                    }

                    @Override
                    public void restore(ComponentState state) {
                        var counter = (CounterState) state;
                        count = counter.count();
                        lastSequence = counter.lastSequence();
                    }
                }
                """));
    }

    private static void print(String what, long[] valuesNs) {
        long[] sorted = valuesNs.clone();
        Arrays.sort(sorted);
        System.out.printf(Locale.ROOT, "  %-66s p50 %8.1f us  p90 %8.1f us  p99 %8.1f us  max %8.1f us%n", what,
                percentile(sorted, 0.50) / 1e3, percentile(sorted, 0.90) / 1e3, percentile(sorted, 0.99) / 1e3,
                sorted[sorted.length - 1] / 1e3);
    }

    /** The nearest-rank percentile of sorted values. */
    private static long percentile(long[] sorted, double fraction) {
        int rank = (int) Math.ceil(fraction * sorted.length);
        return sorted[Math.max(0, rank - 1)];
    }
}
