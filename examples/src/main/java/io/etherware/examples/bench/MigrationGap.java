package io.etherware.examples.bench;

import io.etherware.core.kernel.EtherwareNode;
import io.etherware.core.message.ContentsTypes;
import io.etherware.core.message.Criticality;
import io.etherware.core.message.Profile;
import io.etherware.core.message.QoS;
import io.etherware.examples.bench.UpgradeGap.Chain;
import io.etherware.examples.bench.UpgradeGap.ChainState;
import io.etherware.examples.bench.UpgradeGap.ChainV1;
import io.etherware.examples.bench.UpgradeGap.Seq;
import io.etherware.rt.scheduling.RealtimeSchedulerConfig;
import io.etherware.rt.scheduling.ThreadSchedulingRule;
import io.etherware.services.management.AccessRule;
import io.etherware.services.management.Management;
import io.etherware.services.management.ManagementConfig;
import io.etherware.services.management.ManagementService;
import io.etherware.services.management.MigrationResult;
import io.etherware.services.network.NetworkConfig;
import io.etherware.services.network.NetworkMessenger;
import java.net.InetSocketAddress;
import java.time.Duration;
import java.util.Locale;
import java.util.Set;
import java.util.concurrent.TimeUnit;

/**
 * The migration gap: the upgrade gap's chain (one message always in flight to the component
 * itself) migrated back and forth between two nodes in this JVM, joined by their
 * NetworkMessengers over TCP on loopback, so the state and the held messages cross a real socket
 * as XML. The gap is the management services': the end of the last message handled at the source
 * to the start of the first handled at the target. From the services module's migration gap
 * harness.
 *
 * <p>Both nodes run the real-time scheduler, as the upgrade row's node does: Table II priorities
 * when {@link BenchConfig#realtimeBursts()}, else ordinary ones. With Table II, the network
 * threads, the target's management dispatcher and the source's worker during the gap run at
 * real-time priorities, so the row measures the protocol (two steps across the network and a
 * relocation) rather than how long ordinary threads wait for a CPU behind the JIT compiler and the
 * collector; with ordinary priorities it measures both.
 */
final class MigrationGap implements GapMeasurement {

    private static final Profile LOOP = Profile.parse("bench-loop[bench=migration]");
    private static final QoS LOOP_QOS = QoS.of(Criticality.MIDDLE);
    /**
     * Warm-up migrations, at most: as many as are measured, up to 200. Each migration runs its
     * code (the steps' encoding and decoding, the restore, the registration) once, so that code
     * reaches the JIT compiler's thresholds only after some hundred migrations: with 30 warm-up
     * ones, the INSTALL step's median fell from 1.3 ms over the first 25 measured to 0.6 ms over
     * the last 75. The warm-up's own gaps are reported beside the row, as the cold figure.
     */
    private static final int MAX_WARMUP = 200;
    private static final Duration CONNECT_TIMEOUT = Duration.ofSeconds(30);

    @Override
    public String id() {
        return "migration";
    }

    /**
     * Lets {@code peer} migrate the loop to and from this node, over the bench's plain-TCP loopback
     * links (which do not authenticate the peer).
     */
    private static ManagementConfig management(String peer) {
        return ManagementConfig.builder().allowRemote(peer, Set.of(AccessRule.Operation.MIGRATE), LOOP.role())
                .allowUnauthenticatedLinks(true).build();
    }

    @Override
    public BenchRow measure(BenchConfig config, int repetitions) throws Exception {
        var types = new ContentsTypes().register("bench.seq", Seq.class).register("bench.chainState", ChainState.class);
        var gapsNs = new long[repetitions];
        int warmup = Math.min(MAX_WARMUP, repetitions);
        var coldNs = new long[warmup];
        int cold = 0;
        // The gap's parts: snapshot and INSTALL round trip, relocation, and from there to the
        // first handling at the target (HANDOVER one way, the forwarded messages, the admission).
        var installNs = new long[repetitions];
        var relocateNs = new long[repetitions];
        var handoverNs = new long[repetitions];
        int measured = 0;
        long held = 0;
        Chain.breaks.set(0);
        ThreadSchedulingRule rule = config.realtimeBursts() ? ThreadSchedulingRule.tableII()
                : ThreadSchedulingRule.nonRealtime(4);
        try (var a = node("bench-mig-a", types, config, rule);
                var aNet = NetworkMessenger.start(a, loopback().build());
                var b = node("bench-mig-b", types, config, rule);
                var bNet = NetworkMessenger.start(b, loopback().peer(aNet.localAddress()).build())) {
            // Each node asks the other to move the loop to it, and receives it from the other.
            ManagementService.install(a, management(b.nodeId()), aNet);
            ManagementService.install(b, management(a.nodeId()), bNet);
            UpgradeGap.quietUpgradeLog(a.nodeId());
            UpgradeGap.quietUpgradeLog(b.nodeId());
            if (!aNet.awaitResolvable(Management.profileOf(b.nodeId()), CONNECT_TIMEOUT)
                    || !bNet.awaitResolvable(Management.profileOf(a.nodeId()), CONNECT_TIMEOUT)) {
                throw new IllegalStateException("the two bench nodes did not reach each other's management service");
            }
            a.add(LOOP, ChainV1::new);
            String[] nodes = {a.nodeId(), b.nodeId()};
            for (int i = -warmup; i < repetitions; i++) {
                int from = Math.floorMod(i, 2);
                MigrationResult result = migrateWhileChained(a, nodes[from], nodes[1 - from]);
                if (result.gapNs() < 0) {
                    continue; // no first handling seen: no gap to count
                }
                if (i < 0) {
                    coldNs[cold++] = result.gapNs();
                } else {
                    installNs[measured] = result.transferNs();
                    relocateNs[measured] = result.relocateNs();
                    handoverNs[measured] = result.gapNs() - result.transferNs() - result.relocateNs();
                    gapsNs[measured++] = result.gapNs();
                    held += result.heldMessages();
                }
            }
        }
        String condition = String.format(Locale.ROOT, "%d migrations back and forth, %s", repetitions,
                config.realtimeBursts() ? "Table II priorities" : "ordinary priorities");
        return GapMeasurement.row(id(), "migration (two nodes, TCP loopback)", condition,
                Percentiles.ofSamples(gapsNs, measured), 2_000,
                String.format(Locale.ROOT, "%d of %d gaps measured after %d warm-up (their gaps, code still"
                        + " compiling: p50/p99 %s); %d messages held and forwarded; %d breaks in the message sequence;"
                        + " parts p50/p99: snapshot+install %s, relocate %s, hand-over to first handling %s", measured,
                        repetitions, warmup, part(coldNs, cold), held, Chain.breaks.get(), part(installNs, measured),
                        part(relocateNs, measured), part(handoverNs, measured)));
    }

    /** p50/p99 of one part of the gap, in µs. */
    private static String part(long[] samplesNs, int count) {
        Percentiles part = Percentiles.ofSamples(samplesNs, count);
        return String.format(Locale.ROOT, "%.0f/%.0f us", part.p50Ns() / 1e3, part.p99Ns() / 1e3);
    }

    private static EtherwareNode node(String nodeId, ContentsTypes types, BenchConfig config,
                                      ThreadSchedulingRule rule) {
        return EtherwareNode.builder().nodeId(nodeId).contentsTypes(types).scheduler(() -> config.realtimeScheduler(
                RealtimeSchedulerConfig.builder().threadSchedulingRule(rule))).build().start();
    }

    private static NetworkConfig.Builder loopback() {
        return NetworkConfig.builder().listen(new InetSocketAddress("127.0.0.1", 0));
    }

    private static MigrationResult migrateWhileChained(EtherwareNode requester, String from, String to)
            throws Exception {
        Chain.ended = false;
        Chain.running = true;
        requester.send(LOOP, new Seq(Chain.lastSequence + 1), LOOP_QOS);
        MigrationResult result = Management.migrate(requester, from, LOOP, to).get(30, TimeUnit.SECONDS);
        Chain.running = false;
        long deadlineNs = System.nanoTime() + TimeUnit.SECONDS.toNanos(10);
        while (!Chain.ended && System.nanoTime() < deadlineNs) { // the message in flight lands, sends nothing more
            TimeUnit.MILLISECONDS.sleep(1);
        }
        return result;
    }
}
