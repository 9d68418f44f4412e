package io.etherware.pendulum.components;

import io.etherware.core.kernel.EtherwareNode;
import io.etherware.core.message.Criticality;
import io.etherware.core.message.Profile;
import io.etherware.core.message.QoS;
import io.etherware.core.message.Tick;
import io.etherware.pendulum.dsp.DspBoard;
import java.util.concurrent.locks.LockSupport;

/**
 * Test stand-in for the Notifier service (which lives in etherware-services, a module
 * pendulum-sim must not depend on): sends a HIGH-criticality {@link Tick} every period, sleeping
 * to absolute release times and skipping missed releases instead of bursting (design decision 7).
 * At each release it also reads the plant's ground truth for the test's assertions; the
 * controller never sees it.
 *
 * <p>Runs on one thread; the counters are written by that thread only and read by others.
 */
final class TestTicker implements Runnable {

    private final EtherwareNode node;
    private final Profile target;
    private final long periodNs;
    private final DspBoard board;
    private volatile boolean stop;
    private volatile long sent;
    private volatile long skipped;
    private volatile double maxAbsTheta2Rad;
    private volatile long maxWakeLatenessNs;

    TestTicker(EtherwareNode node, Profile target, long periodNs, DspBoard board) {
        this.node = node;
        this.target = target;
        this.periodNs = periodNs;
        this.board = board;
    }

    @Override
    public void run() {
        QoS qos = QoS.periodic(Criticality.HIGH, periodNs);
        long originNs = System.nanoTime() + periodNs;
        long sequence = 0;
        while (!stop) {
            long releaseNs = originNs + sequence * periodNs;
            long remainingNs;
            while (!stop && (remainingNs = releaseNs - System.nanoTime()) > 0) {
                LockSupport.parkNanos(remainingNs);
            }
            if (stop) {
                return;
            }
            long lateNs = System.nanoTime() - releaseNs;
            if (lateNs >= periodNs) {
                long missed = lateNs / periodNs;
                skipped += missed;
                sequence += missed;
                continue;
            }
            maxWakeLatenessNs = Math.max(maxWakeLatenessNs, lateNs);
            maxAbsTheta2Rad = Math.max(maxAbsTheta2Rad, Math.abs(board.plantState().theta2Rad()));
            node.send(target, new Tick(releaseNs, sequence, periodNs), qos);
            sent++;
            sequence++;
        }
    }

    void stop() {
        stop = true;
    }

    /** Ticks sent. */
    long sent() {
        return sent;
    }

    /** Releases skipped because the ticker woke a whole period late. */
    long skipped() {
        return skipped;
    }

    /** The largest |θ2| of the plant seen at a release (ground truth). */
    double maxAbsTheta2Rad() {
        return maxAbsTheta2Rad;
    }

    /** The ticker's own worst wake-up lateness. */
    long maxWakeLatenessNs() {
        return maxWakeLatenessNs;
    }
}
