package io.etherware.pendulum.serial;

import io.etherware.pendulum.control.BalanceControl;
import io.etherware.pendulum.dsp.DspBoard;
import java.io.IOException;
import java.util.concurrent.locks.LockSupport;

/**
 * Test helper: the paper's 15 ms balancing loop in real time, sleeping to absolute releases and
 * skipping missed ones (never bursting). It talks to the board only through {@link DspClient};
 * the board's ground truth is read for the test's assertion, after each cycle, never by the loop.
 */
final class RealTimeControlLoop implements Runnable {

    private static final long PERIOD_NS = 15_000_000L;

    private final DspClient client;
    private final BalanceControl control;
    private final DspBoard board;
    private final long durationNs;
    volatile int cycles;
    volatile int failed;
    volatile long skipped;
    volatile double maxAbsTheta2AfterOneSecond;
    volatile Exception error;

    RealTimeControlLoop(DspClient client, BalanceControl control, DspBoard board, long durationNs) {
        this.client = client;
        this.control = control;
        this.board = board;
        this.durationNs = durationNs;
    }

    @Override
    public void run() {
        long startNs = System.nanoTime();
        long release = startNs;
        try {
            while (release - startNs < durationNs) {
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
                release += PERIOD_NS;
                long lateNs = System.nanoTime() - release;
                if (lateNs > 0) {
                    long missed = lateNs / PERIOD_NS + 1;
                    skipped += missed;
                    release += missed * PERIOD_NS;
                }
            }
        } catch (IOException e) {
            error = e;
        }
    }
}
