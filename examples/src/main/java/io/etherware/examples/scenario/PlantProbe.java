package io.etherware.examples.scenario;

import io.etherware.core.time.NodeClock;
import io.etherware.pendulum.dsp.DspBoard;
import io.etherware.pendulum.plant.PendulumState;
import java.util.Arrays;
import java.util.Objects;
import java.util.concurrent.ThreadFactory;
import java.util.concurrent.locks.LockSupport;

/**
 * The experimenter's oscilloscope: samples the simulated plant's true state and the motor's
 * applied torque at a fixed period, for the CSV, the plots and the pass/fail verdict. The
 * controller never sees these values (design decision 9); they are what a camera beside the real
 * pendulum would record, and they keep recording while the controller is starved.
 *
 * <p>Runs on its own thread (give it a real-time priority, see {@link SimThreads}), sleeping to
 * absolute sample times; a wake more than one period late skips the missed samples instead of
 * bursting. It stops by itself when its buffer is full. The sample arrays are written by that
 * thread only; {@link #samples()} copies them and may be called from any thread, as may the
 * volatile live values.
 */
public final class PlantProbe implements AutoCloseable {

    private final DspBoard board;
    private final NodeClock clock;
    private final long periodNs;
    private final double fallThresholdRad;
    private final ScenarioEvents events;
    private final long[] timeNs;
    private final double[] theta1Rad;
    private final double[] theta2Rad;
    private final double[] torqueNm;
    private volatile int size;
    private volatile double lastTheta2Rad;
    private volatile double maxAbsTheta2Rad;
    private volatile boolean running;
    private Thread thread;

    /**
     * A probe keeping up to {@code capacity} samples, one every {@code periodNs}, marking a
     * {@link ScenarioEvent.Kind#FELL} event the first time |θ2| exceeds {@code fallThresholdRad}.
     */
    public PlantProbe(DspBoard board, NodeClock clock, long periodNs, int capacity, double fallThresholdRad,
            ScenarioEvents events) {
        this.board = Objects.requireNonNull(board, "board");
        this.clock = Objects.requireNonNull(clock, "clock");
        this.events = Objects.requireNonNull(events, "events");
        if (periodNs <= 0) {
            throw new IllegalArgumentException("periodNs=" + periodNs + ": must be > 0");
        }
        if (capacity <= 0) {
            throw new IllegalArgumentException("capacity=" + capacity + ": must be > 0");
        }
        this.periodNs = periodNs;
        this.fallThresholdRad = fallThresholdRad;
        this.timeNs = new long[capacity];
        this.theta1Rad = new double[capacity];
        this.theta2Rad = new double[capacity];
        this.torqueNm = new double[capacity];
    }

    /** Starts sampling at {@code firstSampleNs}, on a thread from {@code threads}. */
    public synchronized void start(long firstSampleNs, ThreadFactory threads) {
        if (thread != null) {
            throw new IllegalStateException("the probe is already started");
        }
        running = true;
        thread = threads.newThread(() -> run(firstSampleNs));
        thread.start();
    }

    private void run(long firstSampleNs) {
        long nextNs = firstSampleNs;
        boolean fell = false;
        int n = 0;
        while (running && n < timeNs.length) {
            long remainingNs;
            while (running && (remainingNs = nextNs - clock.nanoTime()) > 0) {
                LockSupport.parkNanos(remainingNs);
            }
            if (!running) {
                return;
            }
            long nowNs = clock.nanoTime();
            PendulumState state = board.plantState();
            double theta2 = state.theta2Rad();
            timeNs[n] = nowNs;
            theta1Rad[n] = state.theta1Rad();
            theta2Rad[n] = theta2;
            torqueNm[n] = board.appliedTorqueNm();
            size = ++n;
            lastTheta2Rad = theta2;
            if (Math.abs(theta2) > maxAbsTheta2Rad) {
                maxAbsTheta2Rad = Math.abs(theta2);
            }
            if (!fell && Math.abs(theta2) > fallThresholdRad) {
                fell = true;
                events.add(nowNs, ScenarioEvent.Kind.FELL, "fell");
            }
            nextNs += periodNs;
            long lateNs = nowNs - nextNs;
            if (lateNs >= 0) {
                nextNs += (lateNs / periodNs + 1) * periodNs; // skip, don't burst
            }
        }
    }

    /** The latest θ2 sampled, 0 before the first sample. */
    public double lastTheta2Rad() {
        return lastTheta2Rad;
    }

    /** The largest |θ2| sampled so far. */
    public double maxAbsTheta2Rad() {
        return maxAbsTheta2Rad;
    }

    /** The samples so far, copied. */
    public ProbeSamples samples() {
        int n = size;
        return new ProbeSamples(Arrays.copyOf(timeNs, n), Arrays.copyOf(theta1Rad, n), Arrays.copyOf(theta2Rad, n),
                Arrays.copyOf(torqueNm, n));
    }

    /** Stops sampling and waits up to a second for the thread. Idempotent. */
    @Override
    public void close() {
        Thread sampling;
        synchronized (this) {
            running = false;
            sampling = thread;
        }
        if (sampling != null) {
            LockSupport.unpark(sampling);
            SimThreads.join(sampling, 1_000L);
        }
    }
}
