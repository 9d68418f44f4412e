package io.etherware.rt.scheduling;

import io.etherware.rt.platform.CpuSet;
import io.etherware.rt.platform.Platform;
import io.etherware.rt.platform.ThreadPolicy;
import java.util.concurrent.TimeUnit;
import java.util.concurrent.locks.LockSupport;
import java.util.function.IntConsumer;

/**
 * The source of periodic HIGH messages in tests, standing for the Notifier: a thread at
 * SCHED_FIFO {@value #PRIORITY} when granted, so ordinary threads saturating the CPUs cannot
 * preempt it between stamping a message and sending it, and sleeping to absolute release times
 * between sends (never spinning). The thread ends with the last send.
 */
final class PeriodicSender {

    static final int PRIORITY = 85;

    private PeriodicSender() {
    }

    /**
     * Calls {@code send} with 0..count-1, one call per period starting now, on a new thread, and
     * waits (at most count periods plus 10 s) for it to finish.
     */
    static void run(int count, long periodNs, IntConsumer send) throws InterruptedException {
        Thread sender = Thread.ofPlatform().name("periodic-sender").start(() -> {
            Platform.current().configureCurrentThread(ThreadPolicy.fifo(PRIORITY), CpuSet.inherit());
            long nextNs = System.nanoTime();
            for (int i = 0; i < count; i++) {
                send.accept(i);
                nextNs += periodNs;
                LockSupport.parkNanos(nextNs - System.nanoTime());
            }
        });
        if (!sender.join(java.time.Duration.ofNanos(count * periodNs + TimeUnit.SECONDS.toNanos(10)))) {
            throw new AssertionError("the periodic sender did not finish");
        }
    }
}
