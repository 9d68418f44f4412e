package io.etherware.services.management;

import example.counter.Chain;
import example.counter.ChainCounter;
import example.counter.Seq;
import io.etherware.core.message.Criticality;
import io.etherware.core.message.Profile;
import io.etherware.core.message.QoS;
import java.util.Arrays;
import java.util.Locale;
import java.util.concurrent.TimeUnit;

/**
 * The migration gap, measured: a component keeps one message in flight to itself (so a message is
 * always waiting when it is quiesced) and is migrated back and forth between two nodes through
 * their management services; prints percentiles of the gap (last message handled at the source to
 * the first handled at the target), of each phase and of the whole request. Both nodes run in this
 * JVM, joined by their NetworkMessengers over TCP on loopback, so the state and the held messages
 * cross a real socket as XML; the nodes share the machine's two cores with everything else. Not
 * part of the test suite; run it as a main:
 *
 * <pre>
 * ./mvnw -q -pl etherware-services -am test-compile dependency:build-classpath \
 *     -Dmdep.outputFile=/tmp/migration-cp.txt -Dmdep.includeScope=test
 * java --enable-native-access=ALL-UNNAMED \
 *     -cp etherware-services/target/test-classes:etherware-services/target/classes:$(cat /tmp/migration-cp.txt) \
 *     io.etherware.services.management.MigrationGapHarness [repetitions]
 * </pre>
 */
public final class MigrationGapHarness {

    private static final Profile LOOP = Profile.parse("loop[harness=migration]");
    private static final QoS LOOP_QOS = QoS.of(Criticality.MIDDLE);
    private static final int WARMUP = 30;

    private MigrationGapHarness() {
    }

    public static void main(String[] args) throws Exception {
        int repetitions = args.length > 0 ? Integer.parseInt(args[0]) : 100;
        long[] gapNs = new long[repetitions];
        long[] prepareNs = new long[repetitions];
        long[] quiesceNs = new long[repetitions];
        long[] transferNs = new long[repetitions];
        long[] relocateNs = new long[repetitions];
        long[] totalNs = new long[repetitions];
        long held = 0;
        int unmeasured = 0;
        ManagementConfig config = MigrationNode.config().build();
        try (var a = MigrationNode.start("gap-a", config);
             var b = MigrationNode.start("gap-b", config, a.address())) {
            a.awaitManagementOf("gap-b");
            b.awaitManagementOf("gap-a");
            a.node.add(LOOP, ChainCounter::new);
            String[] nodes = {"gap-a", "gap-b"};
            for (int i = -WARMUP; i < repetitions; i++) {
                int from = Math.floorMod(i, 2);
                MigrationResult result = migrateWhileChained(a, nodes[from], nodes[1 - from]);
                if (i < 0) {
                    continue;
                }
                if (result.gapNs() < 0) {
                    unmeasured++;
                }
                gapNs[i] = result.gapNs();
                prepareNs[i] = result.prepareNs();
                quiesceNs[i] = result.quiesceNs();
                transferNs[i] = result.transferNs();
                relocateNs[i] = result.relocateNs();
                totalNs[i] = result.totalNs();
                held += result.heldMessages();
            }
        }
        System.out.printf(Locale.ROOT, "migration gap harness: two nodes in one JVM over TCP loopback, scheduler=fifo"
                + " repetitions=%d (after %d warm-up, back and forth) breaks-in-sequence=%d gap-unmeasured=%d"
                + " held-messages=%d cpus=%d%n", repetitions, WARMUP, Chain.breaks.get(), unmeasured, held,
                Runtime.getRuntime().availableProcessors());
        if (!Chain.firstBreaks.isEmpty()) {
            System.out.println("  first breaks (expected->got): " + Chain.firstBreaks);
        }
        print("gap      (last message handled at the source -> first at the target)", gapNs);
        print("prepare  (target loads and constructs; component runs on)", prepareNs);
        print("quiesce  (hold requested -> held at a message boundary)", quiesceNs);
        print("transfer (snapshot, state as XML, restore + register held at target)", transferNs);
        print("relocate (held messages forwarded, profile switched to the target)", relocateNs);
        print("total    (request at the source's service -> hand-over answered)", totalNs);
    }

    private static MigrationResult migrateWhileChained(MigrationNode requester, String from, String to)
            throws Exception {
        Chain.ended = false;
        Chain.running = true;
        requester.node.send(LOOP, new Seq(Chain.lastSequence + 1), LOOP_QOS);
        MigrationResult result = Management.migrate(requester.node, from, LOOP, to).get(30, TimeUnit.SECONDS);
        Chain.running = false;
        while (!Chain.ended) { // the message in flight lands and sends nothing more
            TimeUnit.MILLISECONDS.sleep(1);
        }
        return result;
    }

    private static void print(String what, long[] valuesNs) {
        long[] sorted = valuesNs.clone();
        Arrays.sort(sorted);
        System.out.printf(Locale.ROOT, "  %-72s p50 %8.1f us  p90 %8.1f us  p99 %8.1f us  max %8.1f us%n", what,
                percentile(sorted, 0.50) / 1e3, percentile(sorted, 0.90) / 1e3, percentile(sorted, 0.99) / 1e3,
                sorted[sorted.length - 1] / 1e3);
    }

    /** The nearest-rank percentile of sorted values. */
    private static long percentile(long[] sorted, double fraction) {
        int rank = (int) Math.ceil(fraction * sorted.length);
        return sorted[Math.max(0, rank - 1)];
    }
}
