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
import org.junit.jupiter.api.Test;
import org.junit.jupiter.api.condition.EnabledOnOs;
import org.junit.jupiter.api.condition.OS;

/**
 * The real serial stack without hardware: the DSP simulator serves the master side of a
 * pseudo-terminal, jSerialComm opens the slave like any serial port. Real time on a shared,
 * loaded machine, so the margins are generous.
 */
@EnabledOnOs(OS.LINUX)
class PseudoTerminalJSerialCommIT {

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
            // Both loops sleep between short bursts of work (no spinning), so they may run under
            // SCHED_FIFO on this shared, loaded machine; without it they run on, warned.
            board.startRealTime(NodeClock.system(), RealTimePriority.fifoThreads("dsp-board", 20));
            // Generous timeout: on a loaded box a thread may wake late.
            DspClient client = new DspClient(port, NodeClock.system(),
                    DspClient.Config.defaults().withTimeout(java.time.Duration.ofMillis(12), 1));
            BalanceControl control = new BalanceControl(GainSet.v2Tight(parameters), 0.0,
                    DspBoardConfig.DEFAULT_MAX_TORQUE_NM,
                    VelocityEstimator.DEFAULT_FILTER_TIME_CONSTANT_NS);
            RealTimeControlLoop loop = new RealTimeControlLoop(client, control, board, 4_000_000_000L);
            Thread controller = RealTimePriority.fifoThreads("controller", 15).newThread(loop);
            controller.start();
            controller.join(30_000L);

            BoardStatus status = client.readStatus();
            System.out.printf("pty + jSerialComm: %d cycles, %d failed, %d releases skipped,"
                    + " max |θ2| after 1 s %.4f, final %s, board %s, late board cycles %d,"
                    + " client %s%n", loop.cycles, loop.failed, loop.skipped,
                    loop.maxAbsTheta2AfterOneSecond, board.plantState(), status,
                    board.lateCycles(), client.counters());
            assertTrue(loop.error == null, () -> "control loop failed: " + loop.error);
            assertTrue(loop.maxAbsTheta2AfterOneSecond < 0.15, () -> "the pendulum wandered or fell");
            assertTrue(loop.cycles >= 100, "cycles " + loop.cycles);
            assertTrue(loop.failed < loop.cycles / 4, "failed " + loop.failed + " of " + loop.cycles);
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
