package io.etherware.rt.scheduling;

import java.util.ArrayList;
import java.util.List;
import java.util.concurrent.TimeUnit;
import java.util.concurrent.locks.LockSupport;

/**
 * Ordinary (SCHED_OTHER) threads that keep every core busy, each bounded by its own deadline so a
 * failed test cannot leave them running. Never at real-time priority.
 *
 * <p>{@link #occupyHalfBusy} is the one burn allowed on a real-time dispatcher: bounded, and it
 * gives the CPU back half of the time.
 */
final class Burners {

    private static final long SLICE_NS = TimeUnit.MILLISECONDS.toNanos(2);
    private static volatile long handlerSink;

    private final List<Thread> threads;
    private volatile boolean stop;
    /** Published so the burn loop is not optimized away. */
    private volatile long sink;

    private Burners(int count, long maxMs) {
        threads = new ArrayList<>();
        for (int i = 0; i < count; i++) {
            threads.add(Thread.ofPlatform().name("burner-" + i).daemon(true).start(() -> burn(maxMs)));
        }
    }

    static Burners start(int count, long maxMs) {
        return new Burners(count, maxMs);
    }

    static Burners none() {
        return new Burners(0, 0);
    }

    private void burn(long maxMs) {
        long endNs = System.nanoTime() + maxMs * 1_000_000L;
        long value = 0;
        while (!stop && System.nanoTime() < endNs) {
            for (int i = 0; i < 10_000; i++) {
                value += i ^ value;
            }
        }
        sink = value;
    }

    /**
     * Holds the calling thread for {@code durationNs} of wall-clock time, alternately burning CPU
     * and sleeping for 2 ms each: a handler that occupies its component and its dispatcher for the
     * whole time, but never keeps a CPU for more than one slice, even at real-time priority.
     */
    static void occupyHalfBusy(long durationNs) {
        long endNs = System.nanoTime() + durationNs;
        long value = 0;
        for (long nowNs = System.nanoTime(); nowNs < endNs; nowNs = System.nanoTime()) {
            long burnUntilNs = Math.min(endNs, nowNs + SLICE_NS);
            while (System.nanoTime() < burnUntilNs) {
                for (int i = 0; i < 1_000; i++) {
                    value += i ^ value;
                }
            }
            long restNs = Math.min(SLICE_NS, endNs - System.nanoTime());
            if (restNs > 0) {
                LockSupport.parkNanos(restNs);
            }
        }
        handlerSink = value;
    }

    void stop() throws InterruptedException {
        stop = true;
        for (Thread thread : threads) {
            thread.join();
        }
    }
}
