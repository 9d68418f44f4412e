package io.etherware.pendulum.components;

import io.etherware.core.kernel.EtherwareNode;
import io.etherware.core.message.Empty;
import io.etherware.core.message.Profile;
import io.etherware.core.message.QoS;
import io.etherware.core.scheduler.FifoScheduler;
import io.etherware.core.time.NodeClock;
import io.etherware.pendulum.control.GainSet;
import io.etherware.pendulum.dsp.DspBoard;
import io.etherware.pendulum.dsp.DspBoardConfig;
import io.etherware.pendulum.plant.PendulumParameters;
import io.etherware.pendulum.plant.PendulumState;
import io.etherware.pendulum.serial.DspClient;
import io.etherware.pendulum.serial.RealTimePriority;
import io.etherware.pendulum.serial.SimulatedSerialLink;
import java.util.concurrent.ThreadFactory;
import java.util.concurrent.TimeUnit;

/**
 * The components in real time: an {@link EtherwareNode} on the original single FIFO dispatcher,
 * the {@link DspProxy} on a real-time {@link SimulatedSerialLink} (115200 baud) to a
 * {@link DspBoard} stepping against the monotonic clock, and a {@link PendulumController} driven
 * by a {@link TestTicker} at 15 ms.
 *
 * <p>With {@code realTimePriorities}, the board (priority 20), the ticker (18) and the node's
 * dispatcher (15) run under SCHED_FIFO through the test helper {@link RealTimePriority}: on this
 * loaded machine the board's thread starves at normal priority. None of them spins. The
 * dispatcher's thread belongs to the FifoScheduler, so a tiny test component raises it from
 * inside, on its first message.
 */
final class RealTimeLoop implements AutoCloseable {

    static final PendulumParameters PARAMETERS = PendulumParameters.defaults();
    static final long PERIOD_NS = 15_000_000L;
    static final ControllerConfig CONFIG = ControllerConfig.defaults();
    private static final Profile PRIORITY_RAISER = Profile.of("test.priority-raiser");

    final SimulatedSerialLink link = SimulatedSerialLink.realTime(SimulatedSerialLink.Config.defaults());
    final DspBoard board;
    final DspClient client;
    final EtherwareNode node;
    final ControlRecorder recorder = new ControlRecorder(100_000);
    final TestTicker ticker;
    private final boolean realTimePriorities;
    private Thread tickerThread;
    private volatile boolean dispatcherRaised;

    RealTimeLoop(PendulumState initial, GainSet gains, boolean realTimePriorities) {
        this.realTimePriorities = realTimePriorities;
        board = new DspBoard(DspBoardConfig.defaults(), PARAMETERS, initial, link.boardEnd());
        client = new DspClient(link.hostEnd(), NodeClock.system(), DspClient.Config.defaults());
        node = EtherwareNode.builder().nodeId("rt").scheduler(() -> new FifoScheduler("rt-dispatcher")).build();
        node.add(DspProxy.DEFAULT_PROFILE, DspProxy.factory(client));
        node.add(PendulumController.DEFAULT_PROFILE, PendulumController.factory(CONFIG, gains, recorder));
        node.add(PRIORITY_RAISER, () -> (message, context) -> {
            dispatcherRaised = RealTimePriority.requestFifo(15);
            context.reply(message, Empty.INSTANCE);
        });
        ticker = new TestTicker(node, PendulumController.DEFAULT_PROFILE, PERIOD_NS, board);
    }

    /**
     * Starts the node, then the board and at once the ticker: the pendulum starts falling when the
     * board starts (θ2 doubles in 90 ms), so nothing slow may come between the two.
     */
    RealTimeLoop start() {
        node.start();
        if (realTimePriorities) {
            node.requestBlocking(PRIORITY_RAISER, Empty.INSTANCE, QoS.NONE, TimeUnit.SECONDS.toNanos(10));
        }
        board.startRealTime(NodeClock.system(), threads("dsp-board", 20));
        tickerThread = threads("test-ticker", 18).newThread(ticker);
        tickerThread.start();
        return this;
    }

    /** Whether the dispatcher got SCHED_FIFO. */
    boolean dispatcherRaised() {
        return dispatcherRaised;
    }

    private ThreadFactory threads(String name, int priority) {
        if (realTimePriorities) {
            return RealTimePriority.fifoThreads(name, priority);
        }
        return runnable -> {
            Thread thread = new Thread(runnable, name);
            thread.setDaemon(true);
            return thread;
        };
    }

    /** Stops the ticker and waits for the cycle in flight to end. */
    void stopTicker() throws InterruptedException {
        ticker.stop();
        if (tickerThread != null) {
            tickerThread.join(5_000L);
        }
        Thread.sleep(3 * PERIOD_NS / 1_000_000L);
    }

    ControllerState controllerState() {
        return (ControllerState) node.snapshotAsync(PendulumController.DEFAULT_PROFILE).join();
    }

    DspProxyCounters proxyCounters() {
        return (DspProxyCounters) node.snapshotAsync(DspProxy.DEFAULT_PROFILE).join();
    }

    @Override
    public void close() throws InterruptedException {
        stopTicker();
        node.close();
        board.close();
        link.hostEnd().close();
        link.boardEnd().close();
    }
}
