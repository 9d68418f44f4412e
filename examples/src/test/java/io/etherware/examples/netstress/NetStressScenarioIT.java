package io.etherware.examples.netstress;

import static org.junit.jupiter.api.Assertions.assertEquals;
import static org.junit.jupiter.api.Assertions.assertFalse;
import static org.junit.jupiter.api.Assertions.assertTrue;
import static org.junit.jupiter.api.Assumptions.assumeTrue;

import io.etherware.examples.scenario.Progress;
import io.etherware.examples.scenario.RunSummary;
import io.etherware.examples.stress.StressConfig;
import io.etherware.examples.stress.StressScenario;
import io.etherware.rt.platform.CpuSet;
import io.etherware.rt.platform.Platform;
import io.etherware.rt.platform.ThreadPolicy;
import java.io.IOException;
import java.nio.file.Files;
import java.nio.file.Path;
import java.util.List;
import java.util.concurrent.atomic.AtomicBoolean;
import org.junit.jupiter.api.Test;

/**
 * The networked stress experiment end to end, shortened to 10 s per run: two JVMs per run (node 2
 * started on this class path), TCP on loopback, the simulated pendulum behind its serial link, a
 * stress task (node 2's half a stress period after node 1's) and allocating load threads on both
 * nodes. With the original Etherware on both
 * nodes the controller waits behind the stress tasks and the pendulum falls; with Etherware-RT on
 * both it stays up, and the loop misses far fewer deadlines. If Etherware-RT's run falls, it runs
 * once more and the second attempt decides (see the comment there: a rare JVM-wide stall, not the
 * scheduler). Needs SCHED_FIFO (root or
 * CAP_SYS_NICE); without it the comparison means nothing and the test is skipped, saying why,
 * except in CI ({@code CI=true}), where it fails.
 *
 * <p>Both runs partition the CPUs ({@code --rt-cpus 1}: every real-time thread of both JVMs on CPU
 * 1, every other thread on CPU 0) and shorten each stress activation to 700 ms ({@code --stress-ms
 * 700}, under the kernel's real-time budget of 950 ms a second on CPU 1), as the README advises for
 * two cores. Without the partition, a real-time thread of one JVM that needs an ordinary thread to
 * go on inside the JVM (the first use of a path, which loads classes) while the other JVM's stress
 * task holds the other core spins until the kernel throttles real-time threads: node 1's Notifier
 * and node 2's HIGH dispatcher were each seen at full CPU for about 0.9 s beside node 2's stress,
 * and Etherware-RT's first attempt fell in 3 of 5 runs (each passed on its retry); with the
 * partition it stood in every one of 13.
 */
class NetStressScenarioIT {

    private static final long RUN_NS = 10_000_000_000L;
    /** Each stress activation: under the real-time budget of the one real-time CPU. */
    private static final long STRESS_WORK_NS = 700_000_000L;
    /**
     * The original Etherware loses at least the stress activations' seconds (node 1's at 2 s and 7 s,
     * node 2's at 4.5 s and 9.5 s: over 3 s, 200 periods, once it falls more): well above this.
     */
    private static final long MIN_FIFO_MISSES = 100;
    /** Etherware-RT's misses (collector safepoints of two loaded JVMs, mostly) times this stay below the FIFO's. */
    private static final long MISS_RATIO = 5;

    @Test
    void shouldKeepThePendulumUpAcrossTheNetworkWithEtherwareRtWhileTheFifoBaselineLetsItFall() throws Exception {
        boolean granted = realtimePrioritiesGranted();
        String refused = "SCHED_FIFO is refused here (needs root, CAP_SYS_NICE or RLIMIT_RTPRIO): without real"
                + " priorities the two runs do not compare schedulers";
        // On a developer's laptop a refusal skips; in CI (CI=true) it fails, so a green CI has proved the claim.
        if ("true".equals(System.getenv("CI"))) {
            assertTrue(granted, refused);
        }
        assumeTrue(granted, refused);
        Path out = Path.of("target", "scenarios-it", "netstress");
        assumeTrue(Runtime.getRuntime().availableProcessors() >= 2, "the partition needs two CPUs");
        StressConfig base = StressConfig.defaults(out).withDurationNs(RUN_NS);
        StressConfig config = base.withRealtimeCpus(CpuSet.of(1)).withStress(base.stressEveryNs(), STRESS_WORK_NS);
        long offsetNs = NetStressScenario.defaultNode2OffsetNs(config);
        var scenario = new NetStressScenario(config, offsetNs,
                label -> new Progress(label, RUN_NS / 1e9, System.out, false));

        scenario.warmUp();
        NetStressRun fifo = scenario.run(StressScenario.Variant.FIFO);
        NetStressRun rt = scenario.run(StressScenario.Variant.RT);
        RunSummary fifoSummary = RunSummary.of(fifo.run());
        RunSummary rtSummary = RunSummary.of(rt.run());
        if (rtSummary.fell()) {
            // A second attempt, once: on the loaded 2-core box about one short run in six stood
            // still for most of a second during a stress task, most likely a JVM-wide stop (a
            // collection's safepoint waiting for an ordinary thread held off the CPU by a stress
            // task; -Xlog:safepoint showed such waits of 140 ms in passing runs), which no
            // scheduler inside the JVM can prevent. A broken scheduler falls every time, as the
            // FIFO baseline does.
            System.out.print("Etherware-RT's first attempt fell; its figures, then a second attempt:\n"
                    + NetStressReport.table(List.of(rt), List.of(rtSummary)));
            rt.run().notes().forEach(System.out::println);
            rt = scenario.run(StressScenario.Variant.RT);
            rtSummary = RunSummary.of(rt.run());
        }
        check(config, offsetNs, fifo, fifoSummary, rt, rtSummary);
    }

    private static void check(StressConfig config, long offsetNs, NetStressRun fifo, RunSummary fifoSummary,
            NetStressRun rt, RunSummary rtSummary) throws IOException {
        Path out = config.out();
        List<Path> written = NetStressReport.write(config, offsetNs, List.of(fifo, rt), List.of(fifoSummary, rtSummary));
        System.out.print(NetStressReport.table(List.of(fifo, rt), List.of(fifoSummary, rtSummary)));
        fifo.run().notes().forEach(System.out::println);
        rt.run().notes().forEach(System.out::println);

        // Both runs were stressed alike, on both nodes: two activations of about a second each.
        for (NetStressRun run : List.of(fifo, rt)) {
            assertEquals(2, run.node1Activations(), () -> "stress activations on node 1 in " + run.run().title());
            assertEquals(2, run.node2Activations(), () -> "stress activations on node 2 in " + run.run().title()
                    + "; node 2's log: " + out.resolve("node-2-" + run.run().key() + ".log"));
        }
        // The original Etherware: the controller waits behind the stress tasks and the pendulum falls.
        assertTrue(fifoSummary.fell(), () -> "the FIFO baseline should fall; max |θ2| " + fifoSummary.maxAbsTheta2Rad());
        assertTrue(fifoSummary.deadlineMisses() >= MIN_FIFO_MISSES, () -> "the FIFO baseline missed only "
                + fifoSummary.deadlineMisses() + " deadlines");
        // Etherware-RT: HIGH Ticks, readings and commands preempt the stress on both nodes; upright
        // throughout. Bounded by the fall threshold, not by the 0.2 rad of the single-node stress
        // test: with two loaded JVMs a stop of one of them is likelier, and one of node 1's (the
        // board's JVM) stopped the world for 474 ms in one run here, after which θ2 reached 0.25 rad
        // and the loop brought it back (typical runs: 0.02 to 0.04 rad).
        assertFalse(rtSummary.fell(), () -> "Etherware-RT let the pendulum fall at " + rtSummary.fellAtS() + " s");
        assertTrue(MISS_RATIO * rtSummary.deadlineMisses() < fifoSummary.deadlineMisses(), () -> "Etherware-RT missed "
                + rtSummary.deadlineMisses() + " deadlines, the FIFO baseline " + fifoSummary.deadlineMisses());
        assertTrue(MISS_RATIO * rt.cyclesLost() < fifo.cyclesLost(), () -> "cycles lost: Etherware-RT "
                + rt.cyclesLost() + ", the FIFO baseline " + fifo.cyclesLost());
        // Node 2's scheduler counted (Etherware-RT's), and the controller's cycles came back to node 1.
        assertTrue(rt.node2Misses() >= 0, "node 2 reported its scheduler's deadline misses");
        assertTrue(rt.run().cycles().size() > 0.9 * RUN_NS / config.periodNs(),
                () -> "node 1 recorded only " + rt.run().cycles().size() + " of node 2's cycles in the RT run");
        assertTrue(written.stream().anyMatch(p -> p.endsWith("netstress-rt.csv")) && Files.size(out.resolve(
                "netstress-rt.csv")) > 0, "the RT run's CSV was written");
    }

    /** Whether a thread of this JVM can get SCHED_FIFO; asked on a short-lived thread of its own. */
    private static boolean realtimePrioritiesGranted() throws InterruptedException {
        var granted = new AtomicBoolean();
        Thread probe = Thread.ofPlatform().name("fifo-probe").start(() -> granted.set(Platform.current()
                .configureCurrentThread(ThreadPolicy.fifo(1), CpuSet.inherit()).isPolicyGranted()));
        probe.join();
        return granted.get();
    }
}
