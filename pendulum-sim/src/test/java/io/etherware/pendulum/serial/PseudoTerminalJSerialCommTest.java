package io.etherware.pendulum.serial;

import static org.junit.jupiter.api.Assertions.assertArrayEquals;
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
import io.etherware.pendulum.serial.internal.PseudoTerminal;
import java.io.ByteArrayOutputStream;
import java.io.IOException;
import java.util.concurrent.locks.LockSupport;
import org.junit.jupiter.api.Test;
import org.junit.jupiter.api.condition.EnabledOnOs;
import org.junit.jupiter.api.condition.OS;

/**
 * The real serial stack without hardware: the DSP simulator serves the master side of a
 * pseudo-terminal, jSerialComm opens the slave like any serial port. Real time on a shared,
 * loaded machine, so the margins are generous.
 */
@EnabledOnOs(OS.LINUX)
class PseudoTerminalJSerialCommTest {

    @Test
    void shouldCarryBytesBothWaysBetweenTheMasterAndJSerialComm() throws IOException {
        try (PseudoTerminal pty = PseudoTerminal.open();
                JSerialCommLink port = JSerialCommLink.open(pty.slavePath(), 115_200)) {
            byte[] hello = {(byte) 0xA5, 0x00, 0x7E, 0x0A, 0x0D, (byte) 0xFF, 0x11, 0x13};
            port.write(hello, 0, hello.length);
            assertArrayEquals(hello, readFully(pty, hello.length));

            byte[] reply = {0x03, (byte) 0x80, 0x0A, 0x04, 0x1A};
            pty.write(reply, 0, reply.length);
            assertArrayEquals(reply, readFully(port, reply.length), "raw mode: no translation");
            assertTrue(pty.slavePath().startsWith("/dev/pts/"), pty.slavePath());
        }
    }

    @Test
    void shouldBalanceThePendulumOverJSerialCommInRealTime() throws Exception {
        PendulumParameters parameters = PendulumParameters.defaults();
        try (PseudoTerminal pty = PseudoTerminal.open();
                JSerialCommLink port = JSerialCommLink.open(pty.slavePath(), 115_200);
                DspBoard board = new DspBoard(DspBoardConfig.defaults(), parameters,
                        new PendulumState(0.0, 0.0, 0.05, 0.0), pty)) {
            board.startRealTime();
            // Generous timeout: on a loaded box the board's thread may wake late.
            DspClient client = new DspClient(port, NodeClock.system(),
                    DspClient.Config.defaults().withTimeout(12_000_000L, 1));
            BalanceControl control = new BalanceControl(GainSet.v2Tight(parameters), 0.0,
                    DspBoardConfig.DEFAULT_MAX_TORQUE_NM,
                    VelocityEstimator.DEFAULT_FILTER_TIME_CONSTANT_NS);

            long periodNs = 15_000_000L;
            long startNs = System.nanoTime();
            long release = startNs;
            int cycles = 0;
            int failed = 0;
            double maxAbsTheta2AfterOneSecond = 0;
            while (release - startNs < 4_000_000_000L) {
                LockSupport.parkNanos(release - System.nanoTime());
                try {
                    Angles angles = client.readAngles();
                    client.setTorque(control.update(angles.theta1Rad(), angles.theta2Rad(),
                            angles.dspTimeUs()));
                } catch (DspTimeoutException e) {
                    failed++;
                }
                cycles++;
                if (System.nanoTime() - startNs > 1_000_000_000L) {
                    maxAbsTheta2AfterOneSecond = Math.max(maxAbsTheta2AfterOneSecond,
                            Math.abs(board.plantState().theta2Rad()));
                }
                release += periodNs;
                long now = System.nanoTime();
                if (now - release > 0) {
                    release += ((now - release) / periodNs + 1) * periodNs; // skip, never burst
                }
            }
            BoardStatus status = client.readStatus();
            System.out.printf("pty + jSerialComm: %d cycles, %d failed, max |θ2| after 1 s %.4f,"
                    + " final %s, board %s, late board cycles %d, client %s%n", cycles, failed,
                    maxAbsTheta2AfterOneSecond, board.plantState(), status, board.lateCycles(),
                    client.counters());
            assertTrue(maxAbsTheta2AfterOneSecond < 0.15, () -> "the pendulum wandered or fell");
            assertTrue(cycles >= 100, "cycles " + cycles);
            assertTrue(failed < cycles / 4, "failed " + failed + " of " + cycles);
            assertTrue(status.torqueCommands() >= cycles - failed - 1);
            assertEquals(0, status.framesRejected(), "a pty does not corrupt bytes");
        }
    }

    private static byte[] readFully(SerialLink link, int length) throws IOException {
        ByteArrayOutputStream out = new ByteArrayOutputStream();
        byte[] buffer = new byte[64];
        long deadline = System.nanoTime() + 5_000_000_000L;
        while (out.size() < length && System.nanoTime() < deadline) {
            int n = link.read(buffer, 0, buffer.length, 100_000_000L);
            out.write(buffer, 0, n);
        }
        return out.toByteArray();
    }
}
