package io.etherware.examples.bench;

import io.etherware.core.component.Component;
import io.etherware.core.component.ComponentContext;
import io.etherware.core.component.ComponentState;
import io.etherware.core.kernel.EtherwareNode;
import io.etherware.core.message.Contents;
import io.etherware.core.message.Criticality;
import io.etherware.core.message.Message;
import io.etherware.core.message.Profile;
import io.etherware.core.message.QoS;
import io.etherware.rt.scheduling.RealtimeSchedulerConfig;
import io.etherware.rt.scheduling.ThreadSchedulingRule;
import io.etherware.services.management.Implementation;
import io.etherware.services.management.Management;
import io.etherware.services.management.ManagementConfig;
import io.etherware.services.management.ManagementService;
import io.etherware.services.management.UpgradeResult;
import java.util.Locale;
import java.util.concurrent.TimeUnit;
import java.util.concurrent.atomic.AtomicLong;
import org.slf4j.LoggerFactory;

/**
 * The upgrade gap: a component keeps one message in flight to itself (so a message is always
 * waiting when the swap happens) and is upgraded through the management service again and again,
 * alternating between two warmed-up classes on the class path. The gap is the management
 * service's: the end of the old logic's last message to the start of the new logic's first.
 * From the services module's upgrade gap harness.
 *
 * <p>On the real-time scheduler; its dispatchers run at their Table II priorities when
 * {@link BenchConfig#realtimeBursts()}, else at ordinary priorities. The chain runs only from just
 * before each request to its answer.
 */
final class UpgradeGap implements GapMeasurement {

    private static final Profile LOOP = Profile.parse("bench-loop[bench=gap]");
    private static final QoS LOOP_QOS = QoS.of(Criticality.MIDDLE);
    private static final int MAX_WARMUP = 50;

    @Override
    public String id() {
        return "upgrade";
    }

    @Override
    public BenchRow measure(BenchConfig config, int repetitions) throws Exception {
        ThreadSchedulingRule rule = config.realtimeBursts() ? ThreadSchedulingRule.tableII()
                : ThreadSchedulingRule.nonRealtime(4);
        Implementation[] implementations = {Implementation.ofClass(ChainV2.class), Implementation.ofClass(ChainV1.class)};
        var gapsNs = new long[repetitions];
        int measured = 0;
        int warmup = Math.min(MAX_WARMUP, repetitions);
        Chain.breaks.set(0);
        try (var node = EtherwareNode.builder().nodeId("bench-gap").scheduler(() -> config.realtimeScheduler(
                RealtimeSchedulerConfig.builder().threadSchedulingRule(rule))).build()) {
            ManagementService.install(node, ManagementConfig.defaults());
            quietUpgradeLog(node.nodeId());
            node.add(LOOP, ChainV1::new);
            node.start();
            for (int i = -warmup; i < repetitions; i++) {
                UpgradeResult result = upgradeWhileChained(node, implementations[Math.floorMod(i, 2)]);
                if (i >= 0 && result.gapNs() >= 0) {
                    gapsNs[measured++] = result.gapNs();
                }
            }
        }
        String condition = String.format(Locale.ROOT, "%d upgrades, %s", repetitions,
                config.realtimeBursts() ? "Table II priorities" : "ordinary priorities");
        return GapMeasurement.row(id(), "upgrade (management service, class path)", condition,
                Percentiles.ofSamples(gapsNs, measured), 200, String.format(Locale.ROOT,
                        "%d of %d gaps measured after %d warm-up; %d breaks in the message sequence", measured,
                        repetitions, warmup, Chain.breaks.get()));
    }

    /**
     * The management service logs each upgrade at INFO, hundreds here; the row reports them, so
     * only the service's warnings are kept (when Logback is the binding).
     */
    static void quietUpgradeLog(String nodeId) {
        if (LoggerFactory.getLogger("etherware.component." + Management.profileOf(nodeId))
                instanceof ch.qos.logback.classic.Logger logger) {
            logger.setLevel(ch.qos.logback.classic.Level.WARN);
        }
    }

    private static UpgradeResult upgradeWhileChained(EtherwareNode node, Implementation implementation)
            throws Exception {
        Chain.ended = false;
        Chain.running = true;
        node.send(LOOP, new Seq(Chain.lastSequence + 1), LOOP_QOS);
        UpgradeResult result = Management.upgrade(node, node.nodeId(), LOOP, implementation).get(30, TimeUnit.SECONDS);
        Chain.running = false;
        long deadlineNs = System.nanoTime() + TimeUnit.SECONDS.toNanos(10);
        while (!Chain.ended && System.nanoTime() < deadlineNs) { // the message in flight lands, sends nothing more
            TimeUnit.MILLISECONDS.sleep(1);
        }
        return result;
    }

    /** The chain's message: the next sequence number. */
    public record Seq(long value) implements Contents {
    }

    /**
     * The chain's state, handed from the old logic to the new.
     *
     * @param count        messages handled
     * @param lastSequence the last sequence number handled
     */
    public record ChainState(long count, long lastSequence) implements ComponentState {
    }

    /** The switch and the counters the chain's versions share. */
    static final class Chain {
        static volatile boolean running;
        static volatile boolean ended = true;
        static volatile long lastSequence = -1;
        static final AtomicLong breaks = new AtomicLong();

        private Chain() {
        }
    }

    /**
     * Keeps exactly one message in flight to itself while the chain runs and counts sequence
     * numbers that do not follow (lost, duplicated or reordered across a swap). Called on its
     * dispatcher, one message at a time.
     */
    public static class ChainV1 implements Component {
        private long count;
        private long lastSequence = -1;

        @Override
        public void onMessage(Message message, ComponentContext context) {
            if (!(message.contents() instanceof Seq seq)) {
                return;
            }
            if (lastSequence >= 0 && seq.value() != lastSequence + 1) {
                Chain.breaks.incrementAndGet();
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
            return new ChainState(count, lastSequence);
        }

        @Override
        public void restore(ComponentState state) {
            var chain = (ChainState) state;
            count = chain.count();
            lastSequence = chain.lastSequence();
        }
    }

    /** The same logic under another class, so each upgrade really swaps the class. */
    public static class ChainV2 extends ChainV1 {
    }
}
