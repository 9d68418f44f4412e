package io.etherware.pendulum.dsp;

import static org.junit.jupiter.api.Assertions.assertEquals;
import static org.junit.jupiter.api.Assertions.assertTrue;

import io.etherware.pendulum.control.BalanceControl;
import io.etherware.pendulum.control.GainSet;
import io.etherware.pendulum.control.VelocityEstimator;
import io.etherware.pendulum.plant.PendulumParameters;
import io.etherware.pendulum.plant.PendulumState;
import io.etherware.pendulum.serial.BoardStatus;
import io.etherware.pendulum.serial.DspClient;
import io.etherware.pendulum.serial.SimulatedSerialLink;
import org.junit.jupiter.api.Test;
import org.junit.jupiter.params.ParameterizedTest;
import org.junit.jupiter.params.provider.CsvSource;

/**
 * The whole loop, deterministic: controller → DspClient → simulated serial cable → DSP board →
 * plant, and back. The controller sees only encoder counts and board time stamps.
 */
class ClosedLoopLockStepTest {

    static final PendulumParameters PARAMETERS = PendulumParameters.defaults();
    static final PendulumState TILTED = new PendulumState(0.0, 0.0, 0.05, 0.0);
    static final long SECOND_NS = 1_000_000_000L;

    static GainSet gains(String version) {
        return version.equals("V1") ? GainSet.v1Soft(PARAMETERS) : GainSet.v2Tight(PARAMETERS);
    }

    static BalanceControl controller(GainSet gains) {
        return new BalanceControl(gains, 0.0, DspBoardConfig.DEFAULT_MAX_TORQUE_NM,
                VelocityEstimator.DEFAULT_FILTER_TIME_CONSTANT_NS);
    }

    /** 15 ms over the paper's 115200 baud; 1 ms needs a faster line (a cycle is ~45 bytes) and board. */
    static LockStepRig rig(long periodNs, SimulatedSerialLink.Config link) {
        boolean fast = periodNs < 5_000_000L;
        DspBoardConfig board = fast ? DspBoardConfig.defaults().withStep(java.time.Duration.ofNanos(100_000L)) : DspBoardConfig.defaults();
        return new LockStepRig(fast ? link.withBaudRate(921_600) : link, board, TILTED);
    }

    @ParameterizedTest(name = "{0} at {1} ns")
    @CsvSource({"V1, 15000000", "V2, 15000000", "V1, 1000000", "V2, 1000000"})
    void shouldSettleWithinOneHundredthOfARadianInUnderThreeSeconds(String version, long periodNs) {
        LockStepRig rig = rig(periodNs, SimulatedSerialLink.Config.defaults());
        LockStepRig.Run run = rig.control(controller(gains(version)), periodNs, 6 * SECOND_NS);

        double settledS = rig.probe.lastOutsideBandNs * 1e-9;
        System.out.printf("%s at %.0f ms: settled within 0.01 rad after %.3f s, max |θ2| %.4f,"
                + " final %s, %s%n", version, periodNs / 1e6, settledS, rig.probe.maxAbsTheta2Rad,
                rig.board.plantState(), run);
        assertTrue(rig.probe.lastOutsideBandNs < 3 * SECOND_NS, () -> "settled after " + settledS + " s");
        assertEquals(0, run.timeouts());
        assertEquals(0, run.overruns(), "every cycle fits in its period");
        assertEquals(0, rig.board.status().watchdogTrips());
        assertTrue(Math.abs(rig.board.plantState().theta1Rad()) < 0.2, () -> "arm " + rig.board.plantState());
    }

    @Test
    void shouldSettleFasterWithTheTightGainsThanWithTheSoftOnes() {
        long periodNs = 15_000_000L;
        LockStepRig soft = rig(periodNs, SimulatedSerialLink.Config.defaults());
        soft.control(controller(gains("V1")), periodNs, 4 * SECOND_NS);
        LockStepRig tight = rig(periodNs, SimulatedSerialLink.Config.defaults());
        tight.control(controller(gains("V2")), periodNs, 4 * SECOND_NS);
        assertTrue(tight.probe.lastOutsideBandNs < 0.75 * soft.probe.lastOutsideBandNs,
                () -> "tight " + tight.probe.lastOutsideBandNs + " ns, soft " + soft.probe.lastOutsideBandNs + " ns");
    }

    @Test
    void shouldFallWhenTheControllerPausesForOneSecond() {
        long periodNs = 15_000_000L;
        LockStepRig rig = rig(periodNs, SimulatedSerialLink.Config.defaults());
        BalanceControl control = controller(gains("V1"));
        rig.control(control, periodNs, SECOND_NS);
        assertTrue(Math.abs(rig.board.plantState().theta2Rad()) < 0.05, "upright before the pause");

        rig.probe.resetWindow();
        rig.clock.advanceTo(rig.clock.nanoTime() + SECOND_NS);

        System.out.printf("controller paused 1 s: max |θ2| %.3f rad%n", rig.probe.maxAbsTheta2Rad);
        assertTrue(rig.probe.maxAbsTheta2Rad > 0.5, () -> "max |θ2| " + rig.probe.maxAbsTheta2Rad);
        assertTrue(rig.board.status().watchdogFault(), "the watchdog cut the motor meanwhile");
    }

    @Test
    void shouldStayUprightAndRejectBadFramesWhenOnePercentOfBytesHaveABitFlipped() {
        long periodNs = 15_000_000L;
        LockStepRig rig = rig(periodNs, SimulatedSerialLink.Config.defaults().withFaults(0.01, 0.0, 2026L));
        BalanceControl control = controller(gains("V2"));
        LockStepRig.Run run = rig.control(control, periodNs, 3 * SECOND_NS);
        rig.probe.resetWindow();
        LockStepRig.Run steady = rig.control(control, periodNs, 7 * SECOND_NS);

        BoardStatus board = rig.board.status();
        DspClient.Counters host = rig.client.counters();
        System.out.printf("1%% bit flips: max |θ2| %.4f after 3 s; board %s; host %s; link %s / %s; runs %s %s%n",
                rig.probe.maxAbsTheta2Rad, board, host, rig.link.hostToBoardCounters(),
                rig.link.boardToHostCounters(), run, steady);
        assertTrue(rig.probe.maxAbsTheta2Rad < 0.05, () -> "max |θ2| " + rig.probe.maxAbsTheta2Rad);
        assertTrue(board.framesRejected() > 10, board::toString);
        assertTrue(host.framesRejected() > 10, host::toString);
        assertTrue(steady.timeouts() > 0, "lost replies were noticed");
        assertEquals(0, rig.probe.unexpectedTorques, "the board never applied a torque nobody sent");
        assertEquals(0, board.watchdogTrips());
    }
}
