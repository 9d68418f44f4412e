package io.etherware.examples.scenario;

import java.util.ArrayList;
import java.util.List;
import java.util.concurrent.atomic.LongAdder;

/**
 * Ordinary load on the machine, the kind every JVM application carries: one SCHED_OTHER thread
 * per requested core computing and allocating as fast as it can, so every core is busy and the
 * garbage collector works throughout. Each thread keeps a ring of its recent allocations alive
 * (a few MiB), so collections copy survivors instead of finding eden empty.
 *
 * <p>The threads are daemons at normal priority (created by a normal-priority thread, so they
 * inherit nothing real-time). {@link #close()} stops them; every loop iteration checks the stop
 * flag, so they end within microseconds. Thread-safe.
 */
public final class CpuLoad implements AutoCloseable {

    /** Longs per allocated block: 8 KiB. */
    private static final int BLOCK_LONGS = 1024;
    /**
     * Passes over each block before the next is allocated: sets the mix of computing and
     * allocating (on the loaded 2-core development box, about 100 MB/s per thread and two young
     * collections a second). Every collection is a safepoint that stops every Java thread,
     * real-time ones included, until the slowest reaches it; at 20 times this rate (one pass)
     * the runs mostly measured HotSpot's time to safepoint with a load thread starved of CPU:
     * stalls of 70 to 200 ms.
     */
    private static final int PASSES = 8;
    /** Blocks each thread keeps alive: 4 MiB. */
    private static final int RING = 512;
    private static final int PUBLISH_EVERY = 1024;

    private final List<Thread> threads = new ArrayList<>();
    private final LongAdder allocatedBytes = new LongAdder();
    private volatile boolean running = true;
    private volatile long sink;

    private CpuLoad() {
    }

    /** Starts {@code threadCount} load threads (0 starts none). */
    public static CpuLoad start(int threadCount) {
        if (threadCount < 0) {
            throw new IllegalArgumentException("threadCount=" + threadCount + ": must be >= 0");
        }
        CpuLoad load = new CpuLoad();
        for (int i = 0; i < threadCount; i++) {
            Thread thread = Thread.ofPlatform().name("cpu-load-" + i).daemon().unstarted(load::churn);
            load.threads.add(thread);
            thread.start();
        }
        return load;
    }

    private void churn() {
        long[][] ring = new long[RING][];
        long sum = 0;
        int slot = 0;
        int sincePublish = 0;
        while (running) {
            long[] block = new long[BLOCK_LONGS];
            for (int pass = 0; pass < PASSES; pass++) {
                for (int i = 0; i < BLOCK_LONGS; i++) {
                    block[i] = (block[i] ^ sum) * 0x9E3779B97F4A7C15L + i;
                    sum += block[i] >>> 7;
                }
            }
            ring[slot] = block;
            slot = (slot + 1) % RING;
            if (++sincePublish == PUBLISH_EVERY) {
                allocatedBytes.add((long) PUBLISH_EVERY * BLOCK_LONGS * Long.BYTES);
                sincePublish = 0;
            }
        }
        sink = sum;
    }

    /** The number of load threads. */
    public int threadCount() {
        return threads.size();
    }

    /** Bytes allocated so far (to within a thousand blocks per thread). */
    public long allocatedBytes() {
        return allocatedBytes.sum();
    }

    /** Stops the threads and waits for them. Idempotent. */
    @Override
    public void close() {
        running = false;
        for (Thread thread : threads) {
            SimThreads.join(thread, 5_000L);
        }
    }

    @Override
    public String toString() {
        return "CpuLoad[threads=" + threads.size() + ", allocated=" + allocatedBytes() / (1 << 20) + " MiB, sink="
                + (sink & 1) + "]";
    }
}
