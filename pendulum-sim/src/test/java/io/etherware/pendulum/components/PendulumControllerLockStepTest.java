package io.etherware.pendulum.components;

import static io.etherware.pendulum.components.LockStepLoop.PARAMETERS;
import static io.etherware.pendulum.components.LockStepLoop.PERIOD_NS;
import static io.etherware.pendulum.components.LockStepLoop.SECOND_NS;
import static org.junit.jupiter.api.Assertions.assertEquals;
import static org.junit.jupiter.api.Assertions.assertNotEquals;
import static org.junit.jupiter.api.Assertions.assertTrue;

import io.etherware.core.component.Shell;
import io.etherware.core.message.Profile;
import io.etherware.pendulum.control.BalanceControl;
import io.etherware.pendulum.control.GainSet;
import io.etherware.pendulum.control.VelocityEstimatorState;
import io.etherware.pendulum.plant.PendulumState;
import io.etherware.pendulum.serial.Angles;
import java.util.List;
import org.junit.jupiter.api.Test;
import org.junit.jupiter.params.ParameterizedTest;
import org.junit.jupiter.params.provider.ValueSource;

/**
 * The closed loop through a real kernel, deterministic: Tick → controller → ReadAngles →
 * DspProxy → serial bytes → DSP board, and back as AnglesReading → SetTorque. The kernel adds no
 * simulated time, so these runs are exact.
 */
class PendulumControllerLockStepTest {

    static final PendulumState TILTED = new PendulumState(0.0, 0.0, 0.05, 0.0);
    static final GainSet V1 = GainSet.v1Soft(PARAMETERS);
    static final GainSet V2 = GainSet.v2Tight(PARAMETERS);
    static final Profile CONTROLLER = PendulumController.DEFAULT_PROFILE;

    static GainSet gains(int version) {
        return version == 1 ? V1 : V2;
    }

    @ParameterizedTest(name = "V{0}")
    @ValueSource(ints = {1, 2})
    void shouldSettleWithinOneHundredthOfARadianWhenTheLoopRunsThroughTheKernel(int version) {
        try (LockStepLoop loop = new LockStepLoop(TILTED, gains(version))) {
            loop.cycles(400); // 6 s

            ControllerState state = loop.controllerState();
            DspProxyCounters proxy = loop.proxyCounters();
            System.out.printf("kernel lock step V%d: settled within 0.01 rad after %.3f s, max |θ2| %.4f, %s, %s%n",
                    version, loop.probe.lastOutsideBandNs * 1e-9, loop.probe.maxAbsTheta2Rad, state, proxy);
            assertTrue(loop.probe.lastOutsideBandNs < 3 * SECOND_NS, () -> "settled after "
                    + loop.probe.lastOutsideBandNs + " ns");
            assertTrue(loop.probe.maxAbsTheta2Rad < 0.06, () -> "max |θ2| " + loop.probe.maxAbsTheta2Rad);
            assertTrue(Math.abs(loop.board.plantState().theta1Rad()) < 0.2, () -> "arm " + loop.board.plantState());
            assertEquals(400, state.ticks());
            assertEquals(400, state.commands());
            assertEquals(0, state.missedReplies() + state.lateReplies() + state.abandonedCycles() + state.skippedTicks());
            assertEquals(400, proxy.angleReads());
            assertEquals(400, proxy.torqueCommands());
            assertEquals(0, proxy.serialFailures());
            assertEquals(0, loop.board.status().watchdogTrips());
            assertEquals(version, state.gainVersion());
            // Release to reading: 7 bytes out, sampled at the next 0.5 ms board cycle, 19 bytes back.
            ControlCycle first = loop.recorder.cycles().getFirst();
            assertEquals(1_000, first.dspTimeUs());
            assertEquals(1_000_000L + Math.round(19 * 1e10 / 115_200), first.responseNs(), 1_000L);
        }
    }

    @Test
    void shouldFollowExactlyThePlainLoopsTrajectoryBecauseTheKernelAddsNoSimulatedTime() {
        try (LockStepLoop kernel = new LockStepLoop(TILTED, V1);
                LockStepLoop plain = new LockStepLoop(TILTED, V1)) {
            kernel.cycles(200);

            // The same cycles without components: read, compute, command, on the same kind of bench.
            BalanceControl control = new BalanceControl(V1, 0.0, LockStepLoop.CONFIG.maxTorqueNm(),
                    LockStepLoop.CONFIG.filterTimeConstantNs());
            for (int k = 0; k < 200; k++) {
                plain.clock.advanceTo(k * PERIOD_NS);
                try {
                    Angles angles = plain.client.readAngles();
                    plain.client.setTorque(control.update(angles.theta1Rad(), angles.theta2Rad(), angles.dspTimeUs()));
                } catch (java.io.IOException e) {
                    throw new AssertionError(e);
                }
            }
            plain.clock.advanceTo(200 * PERIOD_NS);

            assertEquals(plain.board.plantState(), kernel.board.plantState());
            assertEquals(control.state().estimator(), kernel.controllerState().control().estimator());
        }
    }

    @Test
    void shouldCarryTheStateAndStayUprightWhenSwappedFromV1ToV2() {
        try (LockStepLoop loop = new LockStepLoop(TILTED, V1)) {
            loop.cycles(134); // about 2 s
            ControllerState before = loop.controllerState();
            Shell shell = loop.node.shell(CONTROLLER);

            loop.node.swap(CONTROLLER, PendulumController.factory(LockStepLoop.CONFIG, V2, loop.recorder));
            ControllerState after = loop.controllerState();

            // Everything but the gains carried over, unchanged.
            assertEquals(2, after.gainVersion());
            assertEquals(before.control().estimator(), after.control().estimator());
            assertEquals(before.control().theta1ReferenceRad(), after.control().theta1ReferenceRad());
            assertEquals(before.control().cycles(), after.control().cycles());
            assertEquals(before.ticks(), after.ticks());
            assertEquals(before.lastTickSequence(), after.lastTickSequence());
            assertEquals(0, shell.restartCount());

            loop.probe.resetWindow();
            loop.cycles(200); // 3 s more
            ControllerState end = loop.controllerState();
            VelocityEstimatorState estimator = end.control().estimator();
            System.out.printf("swap V1→V2 in lock step: max |θ2| after the swap %.4f, %s%n",
                    loop.probe.maxAbsTheta2Rad, end);
            assertEquals(334, end.ticks(), "the counters continue");
            assertEquals(334, end.commands());
            assertEquals(before.control().estimator().samples() + 200, estimator.samples(),
                    "the estimator continues: it was not reset");
            assertEquals(0, estimator.discontinuities());
            assertEquals(0, end.abandonedCycles() + end.missedReplies());
            assertTrue(loop.probe.maxAbsTheta2Rad < 0.02, () -> "max |θ2| after the swap " + loop.probe.maxAbsTheta2Rad);

            List<ControlCycle> cycles = loop.recorder.cycles();
            assertEquals(334, cycles.size());
            assertTrue(cycles.subList(0, 134).stream().allMatch(c -> c.gainVersion() == 1));
            assertTrue(cycles.subList(134, 334).stream().allMatch(c -> c.gainVersion() == 2));
            // The first V2 cycle differentiated against the last V1 sample (a reset estimator would
            // report zero rates for its first sample).
            ControlCycle lastV1 = cycles.get(133);
            ControlCycle firstV2 = cycles.get(134);
            assertNotEquals(0.0, firstV2.theta2RateRadPerS());
            assertTrue(Math.abs(firstV2.theta1RateRadPerS() - lastV1.theta1RateRadPerS()) < 0.5,
                    () -> "θ̇1 jumped from " + lastV1.theta1RateRadPerS() + " to " + firstV2.theta1RateRadPerS());
        }
    }

    @Test
    void shouldTightenTheArmFasterAfterTheUpgradeThanWithoutIt() {
        PendulumState armAway = new PendulumState(0.3, 0.0, 0.0, 0.0);
        try (LockStepLoop upgraded = new LockStepLoop(armAway, V1);
                LockStepLoop kept = new LockStepLoop(armAway, V1)) {
            upgraded.cycles(20);
            kept.cycles(20);
            upgraded.node.swap(CONTROLLER, PendulumController.factory(LockStepLoop.CONFIG, V2, upgraded.recorder));
            upgraded.cycles(67); // 1 s
            kept.cycles(67);

            double upgradedArm = Math.abs(upgraded.board.plantState().theta1Rad());
            double keptArm = Math.abs(kept.board.plantState().theta1Rad());
            assertTrue(upgradedArm < 0.5 * keptArm, () -> "arm after 1 s: V2 " + upgradedArm + ", V1 " + keptArm);
        }
    }

    @Test
    void shouldAbandonTheCycleInFlightWhenSwappedBetweenRequestAndReading() {
        try (LockStepLoop loop = new LockStepLoop(TILTED, V1)) {
            loop.cycles(50);
            long commandsBefore = loop.proxyCounters().torqueCommands();

            loop.releaseTick();
            loop.scheduler.runOne(); // the controller handles the Tick and requests the angles
            loop.node.swap(CONTROLLER, PendulumController.factory(LockStepLoop.CONFIG, V2, loop.recorder));
            loop.scheduler.runUntilIdle(); // the proxy reads; the reading goes to the replaced instance

            assertEquals(commandsBefore, loop.proxyCounters().torqueCommands(), "no torque from the abandoned cycle");
            assertEquals(50, loop.controllerState().pendingCycle());

            loop.cycles(100);
            ControllerState state = loop.controllerState();
            assertEquals(1, state.abandonedCycles(), "the successor counted the abandoned cycle");
            assertEquals(150, state.commands());
            assertEquals(151, state.ticks());
            assertEquals(-1, state.pendingCycle());
            assertTrue(Math.abs(loop.board.plantState().theta2Rad()) < 0.01, () -> "" + loop.board.plantState());
            assertEquals(0, loop.node.shell(CONTROLLER).failedCount());
        }
    }

    @Test
    void shouldCountMissedReadingsAndSendNoTorqueWhenTheBoardIsSilent() {
        try (LockStepLoop loop = new LockStepLoop(TILTED, V1, false)) {
            loop.cycles(10);

            ControllerState state = loop.controllerState();
            DspProxyCounters proxy = loop.proxyCounters();
            assertEquals(10, state.missedReplies());
            assertEquals(0, state.commands());
            assertEquals(10, proxy.timeouts());
            assertEquals(0, proxy.torqueCommands());
            assertEquals(0, loop.node.shell(DspProxy.DEFAULT_PROFILE).failedCount(), "a serial timeout is no failure");
            List<ControlCycle> cycles = loop.recorder.cycles();
            assertEquals(10, cycles.size());
            assertTrue(cycles.stream().allMatch(c -> c.outcome() == ControlCycle.Outcome.MISSED && Double.isNaN(c.torqueNm())));
            // Two attempts of 4 ms each, in simulated time: the failure is known within the period.
            assertEquals(8_000_000L, cycles.get(0).responseNs(), 200_000L);
        }
    }

    @Test
    void shouldCountMissedReadingsWhenTheProxyIsNotThere() {
        try (LockStepLoop loop = new LockStepLoop(TILTED, V1)) {
            loop.node.remove(DspProxy.DEFAULT_PROFILE);
            loop.cycles(5);

            ControllerState state = loop.controllerState();
            assertEquals(5, state.missedReplies());
            assertEquals(0, state.commands());
            assertEquals(0, loop.node.shell(CONTROLLER).failedCount());
        }
    }

    @Test
    void shouldCountSkippedReleasesFromGapsInTheTickSequence() {
        try (LockStepLoop loop = new LockStepLoop(TILTED, V1)) {
            loop.cycles(3);
            loop.node.send(CONTROLLER, new io.etherware.core.message.Tick(loop.clock.nanoTime(), 7, PERIOD_NS));
            loop.scheduler.runUntilIdle();

            ControllerState state = loop.controllerState();
            assertEquals(4, state.skippedTicks(), "releases 3 to 6 never came");
            assertEquals(7, state.lastTickSequence());
        }
    }
}
