package io.etherware.examples.stress;

import static org.junit.jupiter.api.Assertions.assertEquals;
import static org.junit.jupiter.api.Assertions.assertFalse;
import static org.junit.jupiter.api.Assertions.assertTrue;
import static org.junit.jupiter.api.Assumptions.assumeTrue;

import io.etherware.examples.output.ComparisonTable;
import io.etherware.examples.scenario.Progress;
import io.etherware.examples.scenario.RunSummary;
import io.etherware.examples.scenario.ScenarioEvent;
import io.etherware.examples.scenario.ScenarioRun;
import io.etherware.rt.platform.CpuSet;
import io.etherware.rt.platform.Platform;
import io.etherware.rt.platform.ThreadPolicy;
import java.nio.file.Files;
import java.nio.file.Path;
import java.util.List;
import java.util.concurrent.atomic.AtomicBoolean;
import org.junit.jupiter.api.Test;

/**
 * The stress experiment end to end, shortened to 10 s per run: real threads, real time, the
 * simulated pendulum behind its serial link, two cores loaded by allocating threads. What it
 * proves is that the scheduler matters: the same node, Ticks and load, with the original FIFO
 * dispatcher the pendulum falls, with Etherware-RT it stays up. Both outcomes are physical and
 * far from their thresholds (see the stress table in the README), so the box's other load does
 * not decide them. Needs SCHED_FIFO (root or CAP_SYS_NICE); without it the comparison means
 * nothing and the test is skipped, saying why, except in CI ({@code CI=true}), where it fails.
 */
class StressScenarioIT {

    private static final long RUN_NS = 10_000_000_000L;

    @Test
    void shouldKeepThePendulumUpWithEtherwareRtWhileTheFifoBaselineLetsItFall() throws Exception {
        boolean granted = realtimePrioritiesGranted();
        String refused = "SCHED_FIFO is refused here (needs root, CAP_SYS_NICE or RLIMIT_RTPRIO): without real"
                + " priorities the two runs do not compare schedulers";
        // On a developer's laptop a refusal skips; in CI (CI=true) it fails, so a green CI has proved the claim.
        if ("true".equals(System.getenv("CI"))) {
            assertTrue(granted, refused);
        }
        assumeTrue(granted, refused);
        Path out = Path.of("target", "scenarios-it", "stress");
        StressConfig config = StressConfig.defaults(out).withDurationNs(RUN_NS);
        var scenario = new StressScenario(config, label -> new Progress(label, RUN_NS / 1e9, System.out, false));

        scenario.warmUp();
        ScenarioRun fifo = scenario.run(StressScenario.Variant.FIFO);
        ScenarioRun rt = scenario.run(StressScenario.Variant.RT);
        RunSummary fifoSummary = RunSummary.of(fifo);
        RunSummary rtSummary = RunSummary.of(rt);
        List<Path> written = StressReport.write(config, List.of(fifo, rt), List.of(fifoSummary, rtSummary));
        System.out.print(ComparisonTable.format(List.of(fifo, rt), List.of(fifoSummary, rtSummary)));
        fifo.notes().forEach(System.out::println);
        rt.notes().forEach(System.out::println);

        // Both runs were stressed alike: two activations of about a second each.
        assertEquals(2, stressStarts(fifo), "stress activations in the FIFO run");
        assertEquals(2, stressStarts(rt), "stress activations in the RT run");
        // The original Etherware: the controller waits behind the stress task and the pendulum falls.
        assertTrue(fifoSummary.fell(), () -> "the FIFO baseline should fall; max |θ2| " + fifoSummary.maxAbsTheta2Rad());
        // Etherware-RT: the HIGH Ticks preempt the stress; the pendulum never leaves ±0.2 rad.
        assertFalse(rtSummary.fell(), () -> "Etherware-RT let the pendulum fall at " + rtSummary.fellAtS() + " s");
        assertTrue(rtSummary.maxAbsTheta2Rad() < 0.2, () -> "Etherware-RT max |θ2| " + rtSummary.maxAbsTheta2Rad());
        assertTrue(rt.samples().size() > 0.9 * RUN_NS / config.periodNs(),
                () -> "the probe sampled the RT run only " + rt.samples().size() + " times");
        assertTrue(written.stream().anyMatch(p -> p.endsWith("stress-rt.csv")) && Files.size(out.resolve(
                "stress-rt.csv")) > 0, "the RT run's CSV was written");
    }

    private static long stressStarts(ScenarioRun run) {
        return run.events().stream().filter(e -> e.kind() == ScenarioEvent.Kind.STRESS_START).count();
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
