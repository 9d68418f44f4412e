package io.etherware.pendulum.components;

import io.etherware.core.kernel.EtherwareNode;
import io.etherware.core.message.Criticality;
import io.etherware.core.message.QoS;
import io.etherware.core.message.Tick;
import io.etherware.pendulum.control.GainSet;
import io.etherware.pendulum.dsp.DspBoard;
import io.etherware.pendulum.dsp.DspBoardConfig;
import io.etherware.pendulum.plant.PendulumParameters;
import io.etherware.pendulum.plant.PendulumState;
import io.etherware.pendulum.serial.DspClient;
import io.etherware.pendulum.serial.SimulatedSerialLink;
import io.etherware.pendulum.sim.LockStepClock;
import java.util.concurrent.TimeUnit;

/**
 * A deterministic bench for the components: an {@link EtherwareNode} on a {@link LockStepScheduler}
 * and a {@link LockStepClock}, with a {@link DspProxy} on a lock-step {@link SimulatedSerialLink}
 * to a {@link DspBoard}, and a {@link PendulumController} activated by Ticks the bench sends at
 * each release. A probe reads the plant's ground truth at every event, for the assertions only.
 *
 * <p>The kernel times requests out on the wall clock, not on the node clock, so the controller
 * here waits up to {@link #WALL_CLOCK_REPLY_TIMEOUT_NS}: a lock-step cycle takes microseconds of
 * real time, and a timeout would make the run depend on the machine's load.
 */
final class LockStepLoop implements AutoCloseable {

    static final PendulumParameters PARAMETERS = PendulumParameters.defaults();
    static final long PERIOD_NS = 15_000_000L;
    static final long SECOND_NS = 1_000_000_000L;
    static final long WALL_CLOCK_REPLY_TIMEOUT_NS = TimeUnit.SECONDS.toNanos(30);
    static final ControllerConfig CONFIG = ControllerConfig.defaults().withReplyTimeout(java.time.Duration.ofNanos(WALL_CLOCK_REPLY_TIMEOUT_NS));

    final LockStepClock clock = new LockStepClock();
    final LockStepScheduler scheduler = new LockStepScheduler();
    final SimulatedSerialLink link;
    final DspBoard board;
    final DspClient client;
    final EtherwareNode node;
    final ControlRecorder recorder = new ControlRecorder(100_000);
    final Probe probe = new Probe();
    private long nextSequence;

    /** Ground truth at every event of the simulation. */
    final class Probe implements LockStepClock.Participant {
        double maxAbsTheta2Rad;
        double bandRad = 0.01;
        long lastOutsideBandNs = -1;

        void resetWindow() {
            maxAbsTheta2Rad = 0.0;
            lastOutsideBandNs = -1;
        }

        @Override
        public long nextEventNs(long nowNs) {
            return Long.MAX_VALUE;
        }

        @Override
        public void advanceTo(long nowNs) {
            if (board == null) {
                return;
            }
            double theta2 = Math.abs(board.plantState().theta2Rad());
            maxAbsTheta2Rad = Math.max(maxAbsTheta2Rad, theta2);
            if (theta2 > bandRad) {
                lastOutsideBandNs = nowNs;
            }
        }
    }

    /** A bench with a board starting in {@code initial}. */
    LockStepLoop(PendulumState initial, GainSet gains) {
        this(initial, gains, true);
    }

    /**
     * A bench.
     *
     * @param withBoard false to leave the link's far end unserved: every exchange times out
     */
    LockStepLoop(PendulumState initial, GainSet gains, boolean withBoard) {
        link = SimulatedSerialLink.lockStep(SimulatedSerialLink.Config.defaults(), clock);
        if (withBoard) {
            board = new DspBoard(DspBoardConfig.defaults(), PARAMETERS, initial, link.boardEnd());
            board.attachTo(clock);
        } else {
            board = null;
        }
        clock.register(probe);
        client = new DspClient(link.hostEnd(), clock, DspClient.Config.defaults());
        node = EtherwareNode.builder().nodeId("lockstep").clock(clock).scheduler(() -> scheduler).build();
        node.add(DspProxy.DEFAULT_PROFILE, DspProxy.factory(client));
        node.add(PendulumController.DEFAULT_PROFILE, PendulumController.factory(CONFIG, gains, recorder));
        node.start();
    }

    /** Moves the clock to the next release and sends its Tick; runs nothing. */
    void releaseTick() {
        long releaseNs = nextSequence * PERIOD_NS;
        clock.advanceTo(releaseNs);
        node.send(PendulumController.DEFAULT_PROFILE, new Tick(releaseNs, nextSequence, PERIOD_NS),
                QoS.periodic(Criticality.HIGH, PERIOD_NS));
        nextSequence++;
    }

    /** One whole cycle: release, then every job until the node is idle. */
    void cycle() {
        releaseTick();
        scheduler.runUntilIdle();
    }

    /** Runs {@code count} cycles, then lets the world run to the end of the last period. */
    void cycles(int count) {
        for (int i = 0; i < count; i++) {
            cycle();
        }
        clock.advanceTo(nextSequence * PERIOD_NS);
    }

    /** The controller's state at its next message boundary. */
    ControllerState controllerState() {
        return (ControllerState) node.snapshotAsync(PendulumController.DEFAULT_PROFILE).join();
    }

    /** The proxy's counters at its next message boundary. */
    DspProxyCounters proxyCounters() {
        return (DspProxyCounters) node.snapshotAsync(DspProxy.DEFAULT_PROFILE).join();
    }

    @Override
    public void close() {
        node.close();
        link.hostEnd().close();
        link.boardEnd().close();
    }
}
