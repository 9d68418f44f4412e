package io.etherware.pendulum.components;

import static org.junit.jupiter.api.Assertions.assertEquals;
import static org.junit.jupiter.api.Assertions.assertInstanceOf;
import static org.junit.jupiter.api.Assertions.assertNotNull;
import static org.junit.jupiter.api.Assertions.assertNull;
import static org.junit.jupiter.api.Assertions.assertThrows;
import static org.junit.jupiter.api.Assertions.assertTrue;

import io.etherware.core.message.Contents;
import io.etherware.core.message.Message;
import io.etherware.core.message.QoS;
import io.etherware.core.message.Text;
import io.etherware.pendulum.control.GainSet;
import io.etherware.pendulum.plant.PendulumState;
import java.util.concurrent.CompletableFuture;
import java.util.concurrent.TimeUnit;
import org.junit.jupiter.api.Test;

/** The proxy alone, in lock step: requests from outside the node, the board behind the link. */
class DspProxyTest {

    static final PendulumState TILTED = new PendulumState(0.25, 0.0, 0.05, 0.0);
    static final GainSet V1 = GainSet.v1Soft(LockStepLoop.PARAMETERS);

    static Contents ask(LockStepLoop bench, Contents request) {
        CompletableFuture<Message> reply = bench.node.request(DspProxy.DEFAULT_PROFILE, request, QoS.NONE,
                TimeUnit.SECONDS.toNanos(30));
        bench.scheduler.runUntilIdle();
        assertTrue(reply.isDone(), "the proxy replied within the step");
        return reply.join().contents();
    }

    @Test
    void shouldReplyWithTheBoardsEncoderSampleWhenAskedForTheAngles() {
        try (LockStepLoop bench = new LockStepLoop(TILTED, V1)) {
            AnglesReading reading = assertInstanceOf(AnglesReading.class, ask(bench, new ReadAngles(42)));

            assertEquals(42, reading.cycle());
            // 4096 counts per revolution, floored like an incremental encoder.
            assertEquals((int) Math.floor(0.25 * 4096 / (2 * Math.PI)), reading.encoder1Counts());
            assertEquals((int) Math.floor(0.05 * 4096 / (2 * Math.PI)), reading.encoder2Counts());
            assertEquals(reading.encoder2Counts() * 2 * Math.PI / 4096, reading.theta2Rad(), 1e-12);
            // Sampled at the first board cycle (0.5 ms steps) after the request's 7 bytes arrived
            // (0.61 ms at 115200 baud 8N1).
            assertEquals(1_000, reading.dspTimeUs());
            assertEquals(1, bench.proxyCounters().angleReads());
        }
    }

    @Test
    void shouldCommandTheBoardAndCountSaturationWhenSentTorques() {
        try (LockStepLoop bench = new LockStepLoop(TILTED, V1)) {
            bench.node.send(DspProxy.DEFAULT_PROFILE, new SetTorque(1, 0.125));
            bench.scheduler.runUntilIdle();
            assertEquals(0.125, bench.board.appliedTorqueNm());

            bench.node.send(DspProxy.DEFAULT_PROFILE, new SetTorque(2, -3.0));
            bench.scheduler.runUntilIdle();
            assertEquals(-0.5, bench.board.appliedTorqueNm(), "clamped by the board to its motor range");

            DspProxyCounters counters = bench.proxyCounters();
            assertEquals(2, counters.torqueCommands());
            assertEquals(1, counters.saturatedCommands());
            assertEquals(-3.0, counters.lastTorqueNm());
        }
    }

    @Test
    void shouldCountAWatchdogRecoveryWhenCommandsResumeAfterTheWatchdogCut() {
        try (LockStepLoop bench = new LockStepLoop(TILTED, V1)) {
            bench.node.send(DspProxy.DEFAULT_PROFILE, new SetTorque(1, 0.01));
            bench.scheduler.runUntilIdle();
            bench.clock.advanceTo(bench.clock.nanoTime() + 150_000_000L);
            assertTrue(bench.board.status().watchdogFault());

            bench.node.send(DspProxy.DEFAULT_PROFILE, new SetTorque(2, 0.01));
            bench.scheduler.runUntilIdle();
            assertEquals(1, bench.proxyCounters().watchdogRecoveries());
        }
    }

    @Test
    void shouldReportItsCountersAndTheBoardsWhenAskedForStatus() {
        try (LockStepLoop bench = new LockStepLoop(TILTED, V1)) {
            ask(bench, new ReadAngles(1));
            bench.node.send(DspProxy.DEFAULT_PROFILE, new SetTorque(1, 0.01));
            bench.scheduler.runUntilIdle();

            DspProxyStatus withBoard = assertInstanceOf(DspProxyStatus.class, ask(bench, new StatusRequest(true)));
            assertNotNull(withBoard.board());
            assertNull(withBoard.boardError());
            assertEquals(1, withBoard.board().torqueCommands());
            assertEquals(1, withBoard.proxy().angleReads());
            assertEquals(3, withBoard.link().requests(), "READ_ANGLES, SET_TORQUE, READ_STATUS");

            DspProxyStatus withoutBoard = assertInstanceOf(DspProxyStatus.class, ask(bench, new StatusRequest(false)));
            assertNull(withoutBoard.board());
            assertEquals(2, withoutBoard.proxy().statusReads());
            assertEquals(3, withoutBoard.link().requests(), "no serial exchange without the board");
        }
    }

    @Test
    void shouldReplyWithATimeoutFaultAndNotFailWhenTheBoardIsSilent() {
        try (LockStepLoop bench = new LockStepLoop(TILTED, V1, false)) {
            DspFault fault = assertInstanceOf(DspFault.class, ask(bench, new ReadAngles(9)));
            assertEquals(DspFault.Kind.TIMEOUT, fault.kind());
            assertEquals(9, fault.cycle());
            assertTrue(fault.detail().contains("READ_ANGLES"), fault.detail());

            DspProxyStatus status = assertInstanceOf(DspProxyStatus.class, ask(bench, new StatusRequest(true)));
            assertNull(status.board());
            assertNotNull(status.boardError());
            assertEquals(2, status.proxy().timeouts());
            assertEquals(0, bench.node.shell(DspProxy.DEFAULT_PROFILE).failedCount());
        }
    }

    @Test
    void shouldReplyWithALinkFaultWhenTheLinkIsClosed() {
        try (LockStepLoop bench = new LockStepLoop(TILTED, V1)) {
            bench.link.hostEnd().close();
            DspFault fault = assertInstanceOf(DspFault.class, ask(bench, new ReadAngles(3)));
            assertEquals(DspFault.Kind.LINK_ERROR, fault.kind());
            assertEquals(1, bench.proxyCounters().linkErrors());
        }
    }

    @Test
    void shouldAnswerARequestItDoesNotServeWithAnUnsupportedFault() {
        try (LockStepLoop bench = new LockStepLoop(TILTED, V1)) {
            DspFault fault = assertInstanceOf(DspFault.class, ask(bench, new Text("what is θ2?")));
            assertEquals(DspFault.Kind.UNSUPPORTED, fault.kind());
            assertTrue(fault.detail().contains("Text"), fault.detail());
            assertEquals(1, bench.proxyCounters().unexpectedMessages());
        }
    }

    @Test
    void shouldKeepCountingWhenRestoredFromItsCounters() throws Exception {
        try (LockStepLoop bench = new LockStepLoop(TILTED, V1)) {
            ask(bench, new ReadAngles(1));
            DspProxyCounters counters = bench.proxyCounters();
            DspProxy fresh = new DspProxy(bench.client);
            fresh.restore(counters);
            assertEquals(counters, fresh.snapshot());
            assertThrows(IllegalArgumentException.class, () -> fresh.restore(
                    new PendulumController(ControllerConfig.defaults(), V1, ControlListener.NONE).snapshot()));
        }
    }
}
