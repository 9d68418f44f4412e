package io.etherware.pendulum.components;

import static org.junit.jupiter.api.Assertions.assertEquals;
import static org.junit.jupiter.api.Assertions.assertTrue;

import io.etherware.core.component.Shell;
import io.etherware.pendulum.control.GainSet;
import io.etherware.pendulum.plant.PendulumState;
import java.util.List;
import org.junit.jupiter.api.Test;

/**
 * The components balancing the pendulum in real time on the original FIFO dispatcher, with a
 * V1→V2 swap half way. Real time on a machine loaded by other builds: the assertions are physical
 * outcomes with generous margins; the timing figures come from {@link PendulumLoopHarness}.
 */
class PendulumControllerRealTimeIT {

    @Test
    void shouldStayUprightInRealTimeAndAcrossASwapFromV1ToV2() throws Exception {
        GainSet v1 = GainSet.v1Soft(RealTimeLoop.PARAMETERS);
        GainSet v2 = GainSet.v2Tight(RealTimeLoop.PARAMETERS);
        try (RealTimeLoop loop = new RealTimeLoop(new PendulumState(0.0, 0.0, 0.05, 0.0), v1, true).start()) {
            Thread.sleep(3_000L);
            ControllerState before = loop.controllerState();
            loop.node.swap(PendulumController.DEFAULT_PROFILE,
                    PendulumController.factory(RealTimeLoop.CONFIG, v2, loop.recorder));
            Thread.sleep(3_000L);
            loop.stopTicker();

            ControllerState end = loop.controllerState();
            DspProxyCounters proxy = loop.proxyCounters();
            List<ControlCycle> cycles = loop.recorder.cycles();
            Shell shell = loop.node.shell(PendulumController.DEFAULT_PROFILE);
            System.out.printf("real time, swap V1→V2 after %d ticks: max |θ2| %.4f rad (ground truth at releases),"
                    + " ticks %d sent %d skipped %d, ticker worst wake %.2f ms, dispatcher SCHED_FIFO %s,%n  %s,%n  %s,"
                    + "%n  board %s%n", before.ticks(), loop.ticker.maxAbsTheta2Rad(), end.ticks(), loop.ticker.sent(),
                    loop.ticker.skipped(), loop.ticker.maxWakeLatenessNs() / 1e6, loop.dispatcherRaised(), end, proxy,
                    loop.board.status());

            assertTrue(loop.ticker.sent() >= 200, () -> "ticks sent " + loop.ticker.sent());
            assertTrue(loop.ticker.maxAbsTheta2Rad() < 0.1, () -> "max |θ2| " + loop.ticker.maxAbsTheta2Rad());
            assertEquals(loop.ticker.sent(), end.ticks(), "every Tick reached a controller; the counters continued");
            assertTrue(end.commands() >= 0.8 * end.ticks(), () -> "commanded " + end.commands() + " of " + end.ticks());
            assertTrue(end.control().estimator().samples() > before.control().estimator().samples() + 100,
                    "the estimator continued after the swap");
            assertEquals(2, end.gainVersion());
            assertEquals(0, shell.failedCount());
            assertEquals(0, shell.restartCount());
            assertTrue(cycles.stream().anyMatch(c -> c.gainVersion() == 2 && c.outcome() == ControlCycle.Outcome.COMMANDED));
            double settledMaxAbsTheta2 = cycles.subList(cycles.size() - 100, cycles.size()).stream()
                    .filter(c -> c.outcome() == ControlCycle.Outcome.COMMANDED)
                    .mapToDouble(c -> Math.abs(c.theta2Rad())).max().orElseThrow();
            assertTrue(settledMaxAbsTheta2 < 0.05, () -> "measured |θ2| in the last 1.5 s up to " + settledMaxAbsTheta2);
        }
    }
}
