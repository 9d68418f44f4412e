package io.etherware.examples.bench;

import java.util.ArrayList;
import java.util.List;
import java.util.concurrent.TimeUnit;

/**
 * Ordinary (SCHED_OTHER) threads that keep every core busy computing, without allocating (so the
 * load does not add collections of its own to what is measured), each bounded by its own
 * deadline so nothing is left spinning if a measurement fails. Never at real-time priority: the
 * threads are created by the caller, who must be an ordinary thread.
 *
 * <p>Thread-safe; {@link #close()} stops the threads and waits for them.
 */
final class SpinLoad implements AutoCloseable {

    private final List<Thread> threads = new ArrayList<>();
    private volatile boolean stop;
    /** Published so the loop is not optimized away. */
    private volatile long sink;

    private SpinLoad() {
    }

    /** Starts {@code threadCount} spinning threads that stop by themselves after {@code maxNs}. */
    static SpinLoad start(int threadCount, long maxNs) {
        var load = new SpinLoad();
        for (int i = 0; i < threadCount; i++) {
            load.threads.add(Thread.ofPlatform().name("bench-load-" + i).daemon(true).start(() -> load.spin(maxNs)));
        }
        return load;
    }

    /** No threads: the idle condition. */
    static SpinLoad none() {
        return new SpinLoad();
    }

    /** One thread per available core. */
    static SpinLoad everyCore(long maxNs) {
        return start(Runtime.getRuntime().availableProcessors(), maxNs);
    }

    private void spin(long maxNs) {
        long endNs = System.nanoTime() + maxNs;
        long value = 0;
        while (!stop && System.nanoTime() < endNs) {
            for (int i = 0; i < 10_000; i++) {
                value += i ^ value;
            }
        }
        sink = value;
    }

    /**
     * Holds the calling thread for {@code durationNs}, burning the CPU: the LOW job of the flood.
     * Bounded by its argument; callers keep it short (100 µs) so even a real-time dispatcher
     * gives the CPU back at once.
     */
    static void burn(long durationNs) {
        long endNs = System.nanoTime() + durationNs;
        while (System.nanoTime() < endNs) {
            Thread.onSpinWait();
        }
    }

    @Override
    public void close() {
        stop = true;
        for (Thread thread : threads) {
            try {
                thread.join(TimeUnit.SECONDS.toMillis(5));
            } catch (InterruptedException e) {
                Thread.currentThread().interrupt();
                return;
            }
        }
    }
}
