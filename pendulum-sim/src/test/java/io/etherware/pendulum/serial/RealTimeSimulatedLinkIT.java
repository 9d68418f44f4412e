package io.etherware.pendulum.serial;

import static org.junit.jupiter.api.Assertions.assertEquals;
import static org.junit.jupiter.api.Assertions.assertTrue;

import io.etherware.core.time.NodeClock;
import io.etherware.pendulum.control.BalanceControl;
import io.etherware.pendulum.control.GainSet;
import io.etherware.pendulum.control.VelocityEstimator;
import io.etherware.pendulum.dsp.DspBoard;
import io.etherware.pendulum.dsp.DspBoardConfig;
import io.etherware.pendulum.plant.PendulumParameters;
import io.etherware.pendulum.plant.PendulumState;
import org.junit.jupiter.api.Test;

/**
 * The board in real time behind a real-time simulated cable at 115200 baud: the setup a node
 * without hardware uses. Real time on a loaded machine: generous margins.
 */
class RealTimeSimulatedLinkIT {

    @Test
    void shouldBalanceThePendulumOverTheSimulatedLinkInRealTime() throws Exception {
        PendulumParameters parameters = PendulumParameters.defaults();
        SimulatedSerialLink link = SimulatedSerialLink.realTime(SimulatedSerialLink.Config.defaults());
        try (DspBoard board = new DspBoard(DspBoardConfig.defaults(), parameters,
                new PendulumState(0.0, 0.0, 0.05, 0.0), link.boardEnd())) {
            board.startRealTime(NodeClock.system(), RealTimePriority.fifoThreads("dsp-board", 20));
            DspClient client = new DspClient(link.hostEnd(), NodeClock.system(),
                    DspClient.Config.defaults().withTimeout(java.time.Duration.ofMillis(12), 1));
            BalanceControl control = new BalanceControl(GainSet.v1Soft(parameters), 0.0,
                    DspBoardConfig.DEFAULT_MAX_TORQUE_NM,
                    VelocityEstimator.DEFAULT_FILTER_TIME_CONSTANT_NS);
            RealTimeControlLoop loop = new RealTimeControlLoop(client, control, board, 3_000_000_000L);
            Thread controller = RealTimePriority.fifoThreads("controller", 15).newThread(loop);
            controller.start();
            controller.join(30_000L);

            System.out.printf("simulated link, real time: %d cycles, %d failed, %d skipped,"
                    + " max |θ2| after 1 s %.4f, board %s, client %s%n", loop.cycles, loop.failed,
                    loop.skipped, loop.maxAbsTheta2AfterOneSecond, board.status(), client.counters());
            assertTrue(loop.error == null, () -> "control loop failed: " + loop.error);
            assertTrue(loop.maxAbsTheta2AfterOneSecond < 0.15, "the pendulum wandered or fell");
            assertTrue(loop.cycles >= 100, "cycles " + loop.cycles);
            assertTrue(loop.failed < loop.cycles / 4, "failed " + loop.failed + " of " + loop.cycles);
            assertEquals(0, board.status().framesRejected());
        }
    }
}
