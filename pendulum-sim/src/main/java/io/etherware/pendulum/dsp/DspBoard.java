package io.etherware.pendulum.dsp;

import io.etherware.core.time.DeadlineSleeper;
import io.etherware.core.time.NodeClock;
import io.etherware.pendulum.plant.PendulumParameters;
import io.etherware.pendulum.plant.PendulumPlant;
import io.etherware.pendulum.plant.PendulumState;
import io.etherware.pendulum.serial.BoardStatus;
import io.etherware.pendulum.serial.DspProtocol;
import io.etherware.pendulum.serial.FrameDecoder;
import io.etherware.pendulum.serial.SerialLink;
import io.etherware.pendulum.sim.LockStepClock;
import java.io.IOException;
import java.util.Objects;
import java.util.concurrent.ThreadFactory;
import java.util.concurrent.locks.LockSupport;
import org.slf4j.Logger;
import org.slf4j.LoggerFactory;

/**
 * The simulated DSP board of the paper's Fig. 6: it owns the pendulum, reads its two encoders,
 * drives its motor, and serves the {@link DspProtocol} on its end of a serial link.
 *
 * <p>The board runs in cycles of {@link DspBoardConfig#stepNs()}. At each cycle boundary it (1)
 * reads the bytes that have arrived and answers every complete frame — encoders are sampled
 * (quantized, floor to a count) at this boundary and stamped with its time; a SET_TORQUE is
 * clamped to the motor range and held from this boundary on (zero-order hold); (2) checks its
 * watchdog: no command for {@link DspBoardConfig#watchdogTimeoutNs()} sets the torque to 0 and
 * raises {@link DspProtocol#FAULT_WATCHDOG} until a command arrives (armed by the first command);
 * (3) integrates the plant over the cycle by RK4.
 *
 * <p>Modes: {@link #attachTo(LockStepClock)} (deterministic lock step, driven by the clock) or
 * {@link #startRealTime} (its own thread steps against the monotonic clock — the physical
 * world — sleeping between cycles and catching up after a late wake, never skipping physics).
 *
 * <p>Thread-safe: the stepping thread and observers synchronize on the board; a cycle holds the
 * lock for a few microseconds. The board does not own the link: closing it stops the thread only.
 * {@link #plantState()} is the simulation's ground truth, for tests and plots: a controller must
 * read the encoders over the link instead (design decision 9).
 */
public final class DspBoard implements AutoCloseable {

    private static final Logger LOG = LoggerFactory.getLogger(DspBoard.class);
    /** Behind the physical clock by more than this is reported once. */
    private static final long LATE_WARNING_NS = 50_000_000L;

    private final DspBoardConfig config;
    private final PendulumPlant plant;
    private final SerialLink link;
    private final double countsPerRadian;
    private final FrameDecoder decoder = new FrameDecoder();
    private final FrameDecoder.Listener onFrame = this::onFrame;
    private final byte[] rxBuffer = new byte[256];
    private final byte[] txFrame = new byte[DspProtocol.MAX_FRAME_BYTES];

    private long originNs;
    private boolean started;
    private double commandedTorqueNm;
    private double appliedTorqueNm;
    private boolean watchdogArmed;
    private boolean watchdogFault;
    private long lastCommandBoardNs;
    private long watchdogTrips;
    private long torqueCommands;
    private long framesIgnored;
    private long transmitErrors;
    private long lateCycles;
    private long maxLagNs;
    private boolean linkFailed;
    private boolean lateWarned;
    private long cycleBoardNs;

    private volatile boolean running;
    private Thread thread;

    /**
     * A board owning a new plant in {@code initial}. It does nothing until started in one of its
     * two modes.
     *
     * @param config     the board's settings; its step is also the plant's integration step
     * @param parameters the pendulum's parameters
     * @param initial    the pendulum's state at the board's time 0
     * @param link       the board's end of the serial link (not closed by the board)
     * @throws NullPointerException when {@code config} or {@code link} is null
     */
    public DspBoard(DspBoardConfig config, PendulumParameters parameters, PendulumState initial,
            SerialLink link) {
        this.config = Objects.requireNonNull(config, "config");
        this.plant = new PendulumPlant(parameters, initial, config.stepNs());
        this.link = Objects.requireNonNull(link, "link");
        this.countsPerRadian = config.countsPerRevolution() / (2.0 * Math.PI);
    }

    /**
     * Lock-step mode: the board runs whenever {@code clock} advances, from its current time. Call
     * it on the thread that drives the clock.
     *
     * @param clock the clock to register with as a participant
     * @throws IllegalStateException when the board was already started, in either mode
     */
    public synchronized void attachTo(LockStepClock clock) {
        markStarted(clock.nanoTime());
        clock.register(new LockStepClock.Participant() {
            @Override
            public long nextEventNs(long nowNs) {
                return nextCycleNs();
            }

            @Override
            public void advanceTo(long nowNs) {
                DspBoard.this.advanceTo(nowNs);
            }
        });
    }

    /**
     * Real-time mode: starts a thread that steps the board against {@code clock}, parking between cycles.
     *
     * @param clock         the physical world's clock, e.g. {@link NodeClock#system()}
     * @param threadFactory makes the stepping thread, e.g. one that raises its priority
     * @throws IllegalStateException when the board was already started, in either mode
     */
    public void startRealTime(NodeClock clock, ThreadFactory threadFactory) {
        startRealTime(clock, threadFactory, DeadlineSleeper.parking(clock));
    }

    /**
     * Real-time mode: starts a thread that steps the board against {@code clock}, sleeping between
     * cycles with {@code sleeper} (e.g. {@code AbsoluteSleeper}, {@code clock_nanosleep} to the
     * cycle boundary). The sleeper is the board thread's alone; it must return within a cycle or so
     * ({@link #close()} waits for it).
     *
     * @param clock         the physical world's clock, e.g. {@link NodeClock#system()}
     * @param threadFactory makes the stepping thread, e.g. one that raises its priority
     * @param sleeper       how the stepping thread sleeps to each cycle boundary on {@code clock}
     * @throws IllegalStateException when the board was already started, in either mode
     */
    public synchronized void startRealTime(NodeClock clock, ThreadFactory threadFactory, DeadlineSleeper sleeper) {
        Objects.requireNonNull(clock, "clock");
        Objects.requireNonNull(sleeper, "sleeper");
        // Logged here, on the caller's thread, not first thing on the stepping one: a JVM's first
        // log line loads the appender's classes, and this thread doing so at the moment the
        // network's real-time reader loaded classes too, both spun inside the JVM at full CPU on
        // both cores for 950 ms (until the kernel's real-time throttling let ordinary threads
        // run): the board fell 950 ms behind and the pendulum fell.
        if (started) {
            throw new IllegalStateException("the board is already running");
        }
        LOG.info("DSP board running in real time: step {} µs, watchdog {} ms, link {}",
                config.stepNs() / 1_000, config.watchdogTimeoutNs() / 1_000_000, link.name());
        markStarted(clock.nanoTime());
        running = true;
        thread = threadFactory.newThread(() -> runRealTime(clock, sleeper));
        thread.start();
    }

    /**
     * Real-time mode on the system clock, with a daemon thread named {@code dsp-board}, parking
     * between cycles.
     *
     * @throws IllegalStateException when the board was already started, in either mode
     */
    public void startRealTime() {
        startRealTime(NodeClock.system(), runnable -> {
            Thread t = new Thread(runnable, "dsp-board");
            t.setDaemon(true);
            return t;
        });
    }

    private void markStarted(long nowNs) {
        if (started) {
            throw new IllegalStateException("the board is already running");
        }
        started = true;
        originNs = nowNs;
    }

    private void runRealTime(NodeClock clock, DeadlineSleeper sleeper) {
        while (running) {
            advanceTo(clock.nanoTime());
            long nextNs = nextCycleNs();
            long wakeNs = nextNs - config.maxSpinNs();
            while (running && clock.nanoTime() - wakeNs < 0) {
                sleeper.sleepUntil(wakeNs);
            }
            // Bounded spin for the last stretch only; a late wake is caught up, not spun for.
            long spinUntilNs = Math.min(nextNs, clock.nanoTime() + config.maxSpinNs());
            while (running && clock.nanoTime() - spinUntilNs < 0) {
                Thread.onSpinWait();
            }
        }
    }

    /** Runs every cycle whose boundary is at or before {@code nowNs}. */
    synchronized void advanceTo(long nowNs) {
        long boardNowNs = nowNs - originNs;
        while (plant.timeNs() <= boardNowNs) {
            long lagNs = boardNowNs - plant.timeNs();
            if (lagNs >= config.stepNs()) {
                lateCycles++;
                maxLagNs = Math.max(maxLagNs, lagNs);
                if (lagNs > LATE_WARNING_NS && !lateWarned) {
                    lateWarned = true;
                    LOG.warn("DSP board {} ms behind the physical clock; catching up (reported once)",
                            lagNs / 1_000_000);
                }
            }
            runCycle(plant.timeNs());
        }
    }

    /** The clock time of the next cycle boundary. */
    private synchronized long nextCycleNs() {
        return originNs + plant.timeNs();
    }

    private void runCycle(long boardNs) {
        cycleBoardNs = boardNs;
        serveLink();
        if (watchdogArmed && !watchdogFault
                && boardNs - lastCommandBoardNs >= config.watchdogTimeoutNs()) {
            watchdogFault = true;
            watchdogTrips++;
            appliedTorqueNm = 0.0;
            LOG.warn("DSP watchdog: no torque command for {} ms; motor off until commands resume",
                    (boardNs - lastCommandBoardNs) / 1_000_000);
        }
        plant.step(appliedTorqueNm);
    }

    private void serveLink() {
        if (linkFailed) {
            return;
        }
        try {
            int n;
            while ((n = link.read(rxBuffer, 0, rxBuffer.length, 0L)) > 0) {
                decoder.accept(rxBuffer, 0, n, onFrame);
            }
        } catch (IOException e) {
            linkFailed = true;
            LOG.error("DSP board stops serving {}: {}; the pendulum keeps moving", link.name(),
                    e.getMessage());
        }
    }

    private void onFrame(int type, byte[] payload, int offset, int length) {
        int sequence = DspProtocol.getU16(payload, offset);
        int frameLength;
        switch (type) {
            case DspProtocol.READ_ANGLES -> frameLength = DspProtocol.encodeAngles(txFrame, sequence,
                    encoderCounts(plant.theta1Rad()), encoderCounts(plant.theta2Rad()),
                    cycleBoardNs / 1_000L);
            case DspProtocol.SET_TORQUE -> frameLength = applyCommand(sequence,
                    DspProtocol.torqueFromWire(DspProtocol.getI32(payload, offset + 2)));
            case DspProtocol.READ_STATUS -> frameLength = statusAt(cycleBoardNs).encode(txFrame, sequence);
            default -> {
                // A valid frame of a board-to-host type: not a request; not acted upon.
                framesIgnored++;
                return;
            }
        }
        try {
            link.write(txFrame, 0, frameLength);
        } catch (IOException e) {
            transmitErrors++;
        }
    }

    private int applyCommand(int sequence, double torqueNm) {
        int flags = watchdogFault ? DspProtocol.ACK_FAULT_WATCHDOG : 0;
        double clamped = Math.max(-config.maxTorqueNm(), Math.min(config.maxTorqueNm(), torqueNm));
        if (clamped != torqueNm) {
            flags |= DspProtocol.ACK_SATURATED;
        }
        if (watchdogFault) {
            LOG.info("DSP watchdog: commands resumed; motor on");
        }
        commandedTorqueNm = torqueNm;
        appliedTorqueNm = clamped;
        watchdogFault = false;
        watchdogArmed = true;
        lastCommandBoardNs = cycleBoardNs;
        torqueCommands++;
        return DspProtocol.encodeAck(txFrame, sequence, flags);
    }

    private int encoderCounts(double angleRad) {
        // An incremental encoder counts whole edges: floor, kept to 32 bits like the hardware counter.
        return (int) (long) Math.floor(angleRad * countsPerRadian);
    }

    private BoardStatus statusAt(long boardNs) {
        return new BoardStatus(watchdogFault ? DspProtocol.FAULT_WATCHDOG : 0, boardNs / 1_000L,
                decoder.framesAccepted() - framesIgnored, decoder.framesRejected() + framesIgnored,
                decoder.bytesDiscarded(), watchdogTrips, torqueCommands, appliedTorqueNm,
                config.countsPerRevolution());
    }

    /**
     * The board's flags and counters now (what a STATUS reply would say).
     *
     * @return a new snapshot, time-stamped at {@link #boardTimeNs()}
     */
    public synchronized BoardStatus status() {
        return statusAt(plant.timeNs());
    }

    /**
     * Ground truth of the simulation, for tests and plots only (see the type's Javadoc).
     *
     * @return the plant's state at {@link #boardTimeNs()}
     */
    public synchronized PendulumState plantState() {
        return plant.state();
    }

    /**
     * The torque the motor applies now.
     *
     * @return the torque, in N·m: the last command clamped to the range, or 0 after a watchdog trip
     */
    public synchronized double appliedTorqueNm() {
        return appliedTorqueNm;
    }

    /**
     * The last torque commanded, before clamping.
     *
     * @return the torque, in N·m; 0 before the first command
     */
    public synchronized double commandedTorqueNm() {
        return commandedTorqueNm;
    }

    /**
     * Board time up to which the plant has been integrated (the next cycle boundary).
     *
     * @return nanoseconds of board time since start
     */
    public synchronized long boardTimeNs() {
        return plant.timeNs();
    }

    /**
     * Cycles run more than one step behind the clock (real-time mode).
     *
     * @return the count since start; 0 in lock step, where time stops at every cycle boundary
     */
    public synchronized long lateCycles() {
        return lateCycles;
    }

    /**
     * The furthest behind the physical clock a cycle ran (real-time mode): how long the board's
     * own thread, the plant, was kept from running, by the machine or the JVM (a safepoint).
     *
     * @return nanoseconds, 0 if no cycle ran a step or more late
     */
    public synchronized long maxLagNs() {
        return maxLagNs;
    }

    /**
     * Replies the link refused to send.
     *
     * @return the count since start
     */
    public synchronized long transmitErrors() {
        return transmitErrors;
    }

    /**
     * Total mechanical energy of the plant (ground truth).
     *
     * @return the energy, in joules
     */
    public synchronized double energyJ() {
        return plant.energyJ();
    }

    /**
     * The board's settings.
     *
     * @return the settings given at construction
     */
    public DspBoardConfig config() {
        return config;
    }

    /** Stops the real-time thread, if any, and waits up to a second for it. Idempotent. */
    @Override
    public void close() {
        Thread stepping;
        synchronized (this) {
            running = false;
            stepping = thread;
            thread = null;
        }
        if (stepping != null) {
            LockSupport.unpark(stepping);
            try {
                stepping.join(1_000L);
            } catch (InterruptedException e) {
                Thread.currentThread().interrupt();
            }
        }
    }
}
