package io.etherware.pendulum.dsp;

import static org.junit.jupiter.api.Assertions.assertEquals;
import static org.junit.jupiter.api.Assertions.assertFalse;
import static org.junit.jupiter.api.Assertions.assertThrows;
import static org.junit.jupiter.api.Assertions.assertTrue;

import io.etherware.pendulum.plant.PendulumState;
import io.etherware.pendulum.serial.Angles;
import io.etherware.pendulum.serial.BoardStatus;
import io.etherware.pendulum.serial.DspException;
import io.etherware.pendulum.serial.DspTimeoutException;
import io.etherware.pendulum.serial.SimulatedSerialLink;
import io.etherware.pendulum.serial.TorqueAck;
import org.junit.jupiter.api.Test;

class DspBoardTest {

    static final long MS = 1_000_000L;

    static LockStepRig rig(PendulumState initial) {
        return new LockStepRig(SimulatedSerialLink.Config.defaults(), DspBoardConfig.defaults(), initial);
    }

    @Test
    void shouldCutTheMotorWithinTheTimeoutPlusOneStepAfterCommandsStop() throws DspException {
        LockStepRig rig = rig(PendulumState.upright(0.0));
        long lastAckNs = 0;
        for (int i = 0; i < 20; i++) {
            rig.clock.advanceTo(i * 15 * MS);
            rig.client.setTorque(0.01);
            lastAckNs = rig.clock.nanoTime();
        }
        assertEquals(0.01, rig.board.appliedTorqueNm(), 1e-9);
        rig.probe.trackZeroTorque = true;

        rig.clock.advanceTo(lastAckNs + 300 * MS);

        long stepNs = rig.board.config().stepNs();
        long cutNs = rig.probe.firstZeroTorqueNs;
        long sinceAck = cutNs - lastAckNs;
        // The command was served at most one wire time (ACK: 7 bytes, 0.6 ms) before its ACK arrived.
        assertTrue(sinceAck <= 100 * MS + stepNs, () -> "motor cut " + sinceAck + " ns after the last ACK");
        assertTrue(sinceAck >= 100 * MS - MS, () -> "motor cut too early: " + sinceAck + " ns");
        BoardStatus status = rig.client.readStatus();
        assertTrue(status.watchdogFault());
        assertEquals(1, status.watchdogTrips());
        assertEquals(0.0, status.appliedTorqueNm());
    }

    @Test
    void shouldClearTheFaultWhenCommandsResume() throws DspException {
        LockStepRig rig = rig(PendulumState.upright(0.0));
        rig.client.setTorque(0.02);
        rig.clock.advanceTo(rig.clock.nanoTime() + 150 * MS);
        assertTrue(rig.board.status().watchdogFault());

        TorqueAck ack = rig.client.setTorque(0.03);

        assertTrue(ack.watchdogWasTripped());
        assertFalse(rig.client.readStatus().watchdogFault());
        assertEquals(0.03, rig.board.appliedTorqueNm(), 1e-9);
    }

    @Test
    void shouldNotTripBeforeTheFirstCommand() {
        LockStepRig rig = rig(PendulumState.upright(0.0));
        rig.clock.advanceTo(500 * MS);
        assertFalse(rig.board.status().watchdogFault());
        assertEquals(0, rig.board.status().watchdogTrips());
    }

    @Test
    void shouldClampTheTorqueToTheMotorRangeAndSaySo() throws DspException {
        LockStepRig rig = rig(PendulumState.upright(0.0));
        TorqueAck ack = rig.client.setTorque(-3.0);
        assertTrue(ack.saturated());
        assertEquals(-DspBoardConfig.DEFAULT_MAX_TORQUE_NM, rig.board.appliedTorqueNm(), 0.0);
        assertEquals(-3.0, rig.board.commandedTorqueNm(), 0.0);
        assertFalse(rig.client.setTorque(0.1).saturated());
    }

    @Test
    void shouldQuantizeTheEncodersToWholeCounts() throws DspException {
        double countRad = 2 * Math.PI / 4096;
        LockStepRig rig = rig(new PendulumState(10.4 * countRad, 0.0, -2.5 * countRad, 0.0));
        Angles angles = rig.client.readAngles();
        assertEquals(10, angles.encoder1Counts());
        assertEquals(-3, angles.encoder2Counts());
        assertEquals(10 * countRad, angles.theta1Rad(), 1e-12);
        assertEquals(-3 * countRad, angles.theta2Rad(), 1e-12);
    }

    @Test
    void shouldStampEachSampleWithTheBoardCycleTime() throws DspException {
        LockStepRig rig = rig(PendulumState.upright(0.0));
        Angles first = rig.client.readAngles();
        rig.clock.advanceTo(15 * MS);
        Angles second = rig.client.readAngles();
        long intervalUs = second.dspTimeUs() - first.dspTimeUs();
        assertEquals(0, first.dspTimeUs() % 500, "stamped at a 0.5 ms cycle boundary");
        assertTrue(intervalUs >= 14_500 && intervalUs <= 15_500, () -> "interval " + intervalUs);
    }

    @Test
    void shouldTimeOutClearlyWhenNoBoardAnswers() {
        var clock = new io.etherware.pendulum.sim.LockStepClock();
        var link = SimulatedSerialLink.lockStep(SimulatedSerialLink.Config.defaults(), clock);
        var client = new io.etherware.pendulum.serial.DspClient(link.hostEnd(), clock,
                io.etherware.pendulum.serial.DspClient.Config.defaults());

        DspTimeoutException error = assertThrows(DspTimeoutException.class, client::readAngles);

        assertTrue(error.getMessage().contains("no ANGLES reply to READ_ANGLES on simulated-host after 2"
                + " attempt(s) of 4000 µs"), error.getMessage());
        assertEquals(8 * MS, clock.nanoTime(), "two attempts of 4 ms in simulated time");
        assertEquals(1, client.counters().failures());
        assertEquals(2, client.counters().timeouts());
    }

    @Test
    void shouldRejectAnInvalidConfigurationNamingTheField() {
        var error = assertThrows(IllegalArgumentException.class,
                () -> DspBoardConfig.defaults().withWatchdogTimeout(java.time.Duration.ofNanos(1_000L)));
        assertTrue(error.getMessage().startsWith("watchdogTimeoutNs=1000"), error.getMessage());
    }
}
