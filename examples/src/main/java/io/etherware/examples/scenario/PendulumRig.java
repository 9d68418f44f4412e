package io.etherware.examples.scenario;

import io.etherware.core.kernel.EtherwareNode;
import io.etherware.core.message.ContentsTypes;
import io.etherware.core.scheduler.Scheduler;
import io.etherware.core.time.NodeClock;
import io.etherware.pendulum.components.ControlListener;
import io.etherware.pendulum.components.ControllerConfig;
import io.etherware.pendulum.components.DspProxy;
import io.etherware.pendulum.components.PendulumContents;
import io.etherware.pendulum.components.PendulumController;
import io.etherware.pendulum.control.GainSet;
import io.etherware.pendulum.dsp.DspBoard;
import io.etherware.pendulum.plant.PendulumParameters;
import io.etherware.pendulum.plant.PendulumState;
import io.etherware.pendulum.serial.DspClient;
import io.etherware.pendulum.serial.SimulatedSerialLink;
import io.etherware.rt.platform.AbsoluteSleeper;
import java.util.Objects;
import java.util.function.Supplier;

/**
 * The pendulum of paper Section VI as the scenarios wire it (Fig. 7 and 10): a {@link DspBoard}
 * stepping the plant in real time behind a {@link SimulatedSerialLink} ({@link PlantWiring}: 115200
 * baud unless the scenario says otherwise), and one
 * {@link EtherwareNode} hosting the {@link DspProxy} on the host end of the link and the
 * {@link PendulumController}. The node's scheduler is the scenario's choice; the board always
 * runs at {@link SimThreads#BOARD_PRIORITY} so the physical world keeps its time whatever the
 * node does.
 *
 * <p>Lifecycle: construct, add further components to {@link #node()}, {@link #start}, then
 * {@link #close}. Not thread-safe apart from what {@link EtherwareNode} and {@link DspBoard}
 * guarantee themselves.
 */
public final class PendulumRig implements AutoCloseable {

    /** The plant of the paper (Section VI-A). */
    public static final PendulumParameters PARAMETERS = PendulumParameters.defaults();

    private final SimulatedSerialLink link;
    private final DspBoard board;
    private final EtherwareNode node;
    private final NodeClock clock = NodeClock.system();

    /**
     * A rig whose node, {@code nodeId}, runs on {@code scheduler}; the plant starts at
     * {@code initial} and the controller computes with {@code gains}, telling {@code listener}
     * about each cycle.
     */
    public PendulumRig(String nodeId, Supplier<? extends Scheduler> scheduler, PendulumState initial, GainSet gains,
            ControlListener listener, PlantWiring wiring) {
        this(nodeId, scheduler, initial, wiring);
        node.add(PendulumController.DEFAULT_PROFILE,
                PendulumController.factory(ControllerConfig.defaults(), gains, listener));
    }

    /**
     * A rig whose node hosts only the {@link DspProxy}: the controller runs elsewhere (paper
     * Fig. 10, where the controller is on another node than the DSPProxy).
     */
    public PendulumRig(String nodeId, Supplier<? extends Scheduler> scheduler, PendulumState initial,
            PlantWiring wiring) {
        Objects.requireNonNull(scheduler, "scheduler");
        link = SimulatedSerialLink.realTime(wiring.link());
        board = new DspBoard(wiring.board(), PARAMETERS, initial, link.boardEnd());
        DspClient client = new DspClient(link.hostEnd(), clock, wiring.client());
        node = EtherwareNode.builder().nodeId(nodeId).scheduler(scheduler).clock(clock)
                .contentsTypes(PendulumContents.register(new ContentsTypes())).build();
        node.add(DspProxy.DEFAULT_PROFILE, DspProxy.factory(client));
    }

    /** The node; add the scenario's other components before {@link #start}. */
    public EtherwareNode node() {
        return node;
    }

    /** The simulated DSP board (and through it the plant's ground truth). */
    public DspBoard board() {
        return board;
    }

    /** The node's clock. */
    public NodeClock clock() {
        return clock;
    }

    /**
     * Starts the node, then the board on a SCHED_FIFO {@link SimThreads#BOARD_PRIORITY} thread.
     * The pendulum starts falling when the board starts (θ2 doubles in about 90 ms): start the
     * Ticks at once afterwards.
     *
     * @return the board's start time, the run's time origin
     */
    public long start(SimThreads threads) {
        node.start();
        return startBoard(threads);
    }

    /**
     * Starts only the board, for a scenario that started the node itself earlier (to connect a
     * controller on another node before the pendulum starts to fall).
     *
     * @return the board's start time, the run's time origin
     */
    public long startBoard(SimThreads threads) {
        long originNs = clock.nanoTime();
        board.startRealTime(clock, threads.fifo("dsp-board", SimThreads.BOARD_PRIORITY),
                AbsoluteSleeper.forClock(clock));
        return originNs;
    }

    /** Closes the node, then stops the board and closes the link. */
    @Override
    public void close() {
        try {
            node.close();
        } finally {
            board.close();
            link.hostEnd().close();
            link.boardEnd().close();
        }
    }
}
