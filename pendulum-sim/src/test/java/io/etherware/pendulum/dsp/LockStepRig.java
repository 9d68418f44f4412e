package io.etherware.pendulum.dsp;

import io.etherware.pendulum.control.BalanceControl;
import io.etherware.pendulum.plant.PendulumParameters;
import io.etherware.pendulum.plant.PendulumState;
import io.etherware.pendulum.serial.Angles;
import io.etherware.pendulum.serial.DspClient;
import io.etherware.pendulum.serial.DspProtocol;
import io.etherware.pendulum.serial.DspTimeoutException;
import io.etherware.pendulum.serial.SimulatedSerialLink;
import io.etherware.pendulum.sim.LockStepClock;
import java.util.HashSet;
import java.util.Set;

/**
 * A deterministic test bench: DSP board and controller host joined by a simulated serial cable,
 * all in the simulated time of one {@link LockStepClock}. The control loop talks to the board
 * only through {@link DspClient}; the rig's probe watches the plant's ground truth at every
 * event for the assertions.
 */
final class LockStepRig {

    final LockStepClock clock = new LockStepClock();
    final SimulatedSerialLink link;
    final DspBoard board;
    final DspClient client;
    final Probe probe = new Probe();

    /** Ground truth and board state, sampled at every event of the simulation. */
    final class Probe implements LockStepClock.Participant {
        double maxAbsTheta2Rad;
        long lastOutsideBandNs = -1;
        double bandRad = 0.01;
        long firstZeroTorqueNs = -1;
        boolean trackZeroTorque;
        final Set<Integer> sentWireTorques = new HashSet<>(Set.of(0));
        long unexpectedTorques;

        void resetWindow() {
            maxAbsTheta2Rad = 0;
            lastOutsideBandNs = -1;
        }

        @Override
        public long nextEventNs(long nowNs) {
            return Long.MAX_VALUE;
        }

        @Override
        public void advanceTo(long nowNs) {
            double theta2 = Math.abs(board.plantState().theta2Rad());
            maxAbsTheta2Rad = Math.max(maxAbsTheta2Rad, theta2);
            if (theta2 > bandRad) {
                lastOutsideBandNs = nowNs;
            }
            if (trackZeroTorque && firstZeroTorqueNs < 0 && board.appliedTorqueNm() == 0.0) {
                firstZeroTorqueNs = nowNs;
            }
            if (!sentWireTorques.contains(DspProtocol.torqueToWire(board.commandedTorqueNm()))) {
                unexpectedTorques++;
            }
        }
    }

    /** What a control run saw. */
    record Run(long cycles, long timeouts, long overruns) {}

    LockStepRig(SimulatedSerialLink.Config linkConfig, DspBoardConfig boardConfig,
            PendulumState initial) {
        link = SimulatedSerialLink.lockStep(linkConfig, clock);
        board = new DspBoard(boardConfig, PendulumParameters.defaults(), initial, link.boardEnd());
        board.attachTo(clock);
        clock.register(probe);
        client = new DspClient(link.hostEnd(), clock,
                DspClient.Config.defaults().withCountsPerRevolution(boardConfig.countsPerRevolution()));
    }

    /**
     * Runs a periodic controller for {@code durationNs}: at each release read the angles, compute,
     * command the torque. A cycle whose reply times out is skipped (the board holds the last
     * torque); releases missed by a long cycle are skipped, not bursted.
     */
    Run control(BalanceControl control, long periodNs, long durationNs) {
        long start = clock.nanoTime();
        long release = start;
        long cycles = 0;
        long timeouts = 0;
        long overruns = 0;
        while (release < start + durationNs) {
            clock.advanceTo(release);
            try {
                Angles angles = client.readAngles();
                double torqueNm = control.update(angles.theta1Rad(), angles.theta2Rad(), angles.dspTimeUs());
                probe.sentWireTorques.add(DspProtocol.torqueToWire(torqueNm));
                client.setTorque(torqueNm);
            } catch (DspTimeoutException e) {
                timeouts++;
            } catch (java.io.IOException e) {
                throw new AssertionError("link failed", e);
            }
            cycles++;
            release += periodNs;
            if (clock.nanoTime() > release) {
                long missed = (clock.nanoTime() - release) / periodNs + 1;
                overruns += missed;
                release += missed * periodNs;
            }
        }
        clock.advanceTo(start + durationNs);
        return new Run(cycles, timeouts, overruns);
    }
}
