package io.etherware.examples.deploy;

import io.etherware.core.time.NodeClock;
import io.etherware.examples.scenario.PendulumRig;
import io.etherware.examples.scenario.PlantWiring;
import io.etherware.examples.scenario.SimThreads;
import io.etherware.pendulum.dsp.DspBoard;
import io.etherware.pendulum.plant.PendulumState;
import io.etherware.pendulum.serial.SerialLink;
import io.etherware.pendulum.serial.SimulatedSerialLink;
import io.etherware.rt.platform.AbsoluteSleeper;
import java.io.IOException;
import java.io.PrintStream;
import java.time.Duration;
import java.util.Locale;
import java.util.concurrent.TimeUnit;
import java.util.concurrent.atomic.AtomicBoolean;
import java.util.concurrent.locks.LockSupport;

/**
 * The simulated DSP board and pendulum of the scenarios, in a deployed node's process, behind a
 * real-time simulated serial line ({@link PlantWiring}). The board starts, on a SCHED_FIFO
 * {@link SimThreads#BOARD_PRIORITY} thread where granted, when the host end is first written to:
 * the pendulum is held upright until the control loop first asks. From then on a thread samples
 * the plant's ground truth every 5 ms and prints a {@value #REPORT} line every report period:
 * {@code PLANT seconds=3.0 theta2=0.0012 maxAbsTheta2=0.0213 fell=false lateCycles=0}.
 *
 * <p>Thread-safe: the node's DSPProxy writes and reads the host end; {@link #close} may come from
 * any thread.
 */
final class SimulatedPlant implements AutoCloseable {

    /** The first word of the plant's report lines. */
    static final String REPORT = "PLANT";
    /** Beyond this |θ2| the pendulum counts as fallen. */
    static final double FALLEN_RAD = 0.5;
    private static final long SAMPLE_NS = TimeUnit.MILLISECONDS.toNanos(5);

    private final SimulatedSerialLink link;
    private final DspBoard board;
    private final NodeClock clock;
    private final PrintStream out;
    private final long reportNs;
    private final SimThreads threads = new SimThreads();
    private final AtomicBoolean started = new AtomicBoolean();
    private final AtomicBoolean closed = new AtomicBoolean();
    private final SerialLink hostEnd;
    private volatile Thread sampler;
    private volatile long startNs;
    /** Written by the sampler only; read by it, and by {@link #close} after joining it. */
    private double maxAbsTheta2;

    SimulatedPlant(PlantWiring wiring, double theta2Rad, Duration report, NodeClock clock, PrintStream out) {
        this.clock = clock;
        this.out = out;
        this.reportNs = report.toNanos();
        link = SimulatedSerialLink.realTime(wiring.link());
        board = new DspBoard(wiring.board(), PendulumRig.PARAMETERS, new PendulumState(0.0, 0.0, theta2Rad, 0.0),
                link.boardEnd());
        maxAbsTheta2 = Math.abs(theta2Rad);
        SerialLink host = link.hostEnd();
        hostEnd = new SerialLink() {
            @Override
            public String name() {
                return host.name();
            }

            @Override
            public void write(byte[] data, int offset, int length) throws IOException {
                startOnce();
                host.write(data, offset, length);
            }

            @Override
            public int read(byte[] buffer, int offset, int length, long timeoutNs) throws IOException {
                return host.read(buffer, offset, length, timeoutNs);
            }

            @Override
            public void close() {
                host.close();
            }
        };
    }

    /** {@return the end the DSPProxy's client uses} */
    SerialLink hostEnd() {
        return hostEnd;
    }

    /** Starts the board at the first write; synchronized with {@link #close}, so a closed board never starts. */
    private void startOnce() {
        if (started.get()) {
            return; // every later write: no lock
        }
        synchronized (this) {
            if (closed.get() || !started.compareAndSet(false, true)) {
                return;
            }
            startNs = clock.nanoTime();
            board.startRealTime(clock, threads.fifo("dsp-board", SimThreads.BOARD_PRIORITY),
                    AbsoluteSleeper.forClock(clock));
            sampler = Thread.ofPlatform().daemon().name("plant-report").start(this::sample);
        }
    }

    private void sample() {
        long nextReport = startNs + reportNs;
        while (!closed.get()) {
            maxAbsTheta2 = Math.max(maxAbsTheta2, Math.abs(board.plantState().theta2Rad()));
            long now = clock.nanoTime();
            if (now >= nextReport) {
                report(now);
                nextReport += reportNs;
            }
            LockSupport.parkNanos(SAMPLE_NS);
        }
    }

    private void report(long nowNs) {
        out.println(String.format(Locale.ROOT, "%s seconds=%.1f theta2=%.4f maxAbsTheta2=%.4f fell=%b lateCycles=%d",
                REPORT, (nowNs - startNs) / 1e9, board.plantState().theta2Rad(), maxAbsTheta2,
                maxAbsTheta2 > FALLEN_RAD, board.lateCycles()));
        out.flush();
    }

    /**
     * Stops the sampler, the board and the line. No last report: the node, and with it the control
     * loop, closed before this, so the pendulum has been falling since. Idempotent.
     */
    @Override
    public void close() {
        synchronized (this) {
            if (!closed.compareAndSet(false, true)) {
                return;
            }
        }
        Thread running = sampler;
        if (running != null) {
            SimThreads.join(running, TimeUnit.SECONDS.toMillis(5));
        }
        board.close();
        link.hostEnd().close();
        link.boardEnd().close();
    }

    @Override
    public String toString() {
        return "simulated DSP board on " + link.hostEnd().name();
    }
}
