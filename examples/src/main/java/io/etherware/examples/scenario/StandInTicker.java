package io.etherware.examples.scenario;

import io.etherware.core.kernel.EtherwareNode;
import io.etherware.core.message.Profile;
import io.etherware.core.message.QoS;
import io.etherware.core.message.Tick;
import java.util.ArrayList;
import java.util.List;
import java.util.Objects;
import java.util.concurrent.ThreadFactory;
import java.util.concurrent.atomic.AtomicLong;
import java.util.concurrent.locks.LockSupport;

/**
 * TEMPORARY stand-in for the Notifier service until it is merged: periodic {@link Tick}s to a
 * profile, with the subscription's QoS, at absolute releases {@code first + k * period}; a release
 * reached half a period late or later is skipped and counted, never sent in a burst. One thread
 * per subscription, sleeping to each release.
 *
 * <p>Thread-safe; {@link #close()} stops every subscription.
 */
public final class StandInTicker implements AutoCloseable {

    private final EtherwareNode node;
    private final ThreadFactory threads;
    private final List<Thread> running = new ArrayList<>();
    private final AtomicLong sent = new AtomicLong();
    private final AtomicLong skipped = new AtomicLong();
    private volatile boolean stop;

    /** Ticks through {@code node}, each subscription on a thread from {@code threads}. */
    public StandInTicker(EtherwareNode node, ThreadFactory threads) {
        this.node = Objects.requireNonNull(node, "node");
        this.threads = Objects.requireNonNull(threads, "threads");
    }

    /** Ticks to {@code target} with {@code qos} (its period must be set) from {@code firstReleaseNs}. */
    public synchronized void periodic(Profile target, QoS qos, long firstReleaseNs) {
        if (!qos.hasPeriod()) {
            throw new IllegalArgumentException("qos=" + qos + ": a periodic Tick needs periodNs > 0");
        }
        Thread thread = threads.newThread(() -> run(target, qos, firstReleaseNs));
        running.add(thread);
        thread.start();
    }

    private void run(Profile target, QoS qos, long firstReleaseNs) {
        long periodNs = qos.periodNs();
        long sequence = 0;
        while (!stop) {
            long releaseNs = firstReleaseNs + sequence * periodNs;
            long remainingNs;
            while (!stop && (remainingNs = releaseNs - node.clock().nanoTime()) > 0) {
                LockSupport.parkNanos(remainingNs);
            }
            if (stop) {
                return;
            }
            long lateNs = node.clock().nanoTime() - releaseNs;
            if (lateNs >= periodNs / 2) {
                long missed = Math.max(1, (lateNs + periodNs / 2) / periodNs);
                skipped.addAndGet(missed);
                sequence += missed;
                continue;
            }
            node.send(target, new Tick(releaseNs, sequence, periodNs), qos);
            sent.incrementAndGet();
            sequence++;
        }
    }

    /** Ticks sent, over all subscriptions. */
    public long sent() {
        return sent.get();
    }

    /** Releases skipped because the ticker woke too late, over all subscriptions. */
    public long skipped() {
        return skipped.get();
    }

    /** Stops every subscription and waits for the threads. Idempotent. */
    @Override
    public void close() {
        List<Thread> copy;
        synchronized (this) {
            stop = true;
            copy = List.copyOf(running);
        }
        for (Thread thread : copy) {
            LockSupport.unpark(thread);
            SimThreads.join(thread, 1_000L);
        }
    }
}
