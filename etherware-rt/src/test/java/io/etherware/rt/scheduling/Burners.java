package io.etherware.rt.scheduling;

import java.util.ArrayList;
import java.util.List;

/**
 * Ordinary (SCHED_OTHER) threads that keep every core busy, each bounded by its own deadline so a
 * failed test cannot leave them running. Never at real-time priority.
 */
final class Burners {

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

    void stop() throws InterruptedException {
        stop = true;
        for (Thread thread : threads) {
            thread.join();
        }
    }
}
