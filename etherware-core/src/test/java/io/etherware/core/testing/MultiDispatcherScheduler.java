package io.etherware.core.testing;

import io.etherware.core.scheduler.Job;
import io.etherware.core.scheduler.JobRunner;
import io.etherware.core.scheduler.Scheduler;
import io.etherware.core.time.NodeClock;
import java.util.ArrayList;
import java.util.List;
import java.util.concurrent.LinkedBlockingQueue;
import java.util.concurrent.TimeUnit;
import java.util.function.ToIntFunction;

/**
 * A test-only scheduler with several dispatcher threads, each with its own FIFO queue, so that one
 * component really receives jobs on several threads at once. Placement is a function of the job
 * (round robin, by sender...). Not real-time: plain threads, blocking queues.
 */
public final class MultiDispatcherScheduler implements Scheduler {

    private final List<LinkedBlockingQueue<Job>> queues = new ArrayList<>();
    private final List<Thread> threads = new ArrayList<>();
    private final ToIntFunction<Job> placement;
    private volatile boolean accepting = true;
    private volatile boolean stopNow;

    public MultiDispatcherScheduler(int dispatchers, ToIntFunction<Job> placement) {
        for (int i = 0; i < dispatchers; i++) {
            queues.add(new LinkedBlockingQueue<>());
        }
        this.placement = placement;
    }

    /** Round robin over the dispatchers, by job sequence. */
    public static MultiDispatcherScheduler roundRobin(int dispatchers) {
        return new MultiDispatcherScheduler(dispatchers, job -> (int) (job.sequence() % dispatchers));
    }

    /** One dispatcher per sender (by hash), so one source's messages share a queue. */
    public static MultiDispatcherScheduler bySender(int dispatchers) {
        return new MultiDispatcherScheduler(dispatchers, job -> {
            var sender = job.message().sender();
            return sender == null ? 0 : Math.floorMod(sender.hashCode(), dispatchers);
        });
    }

    @Override
    public String name() {
        return "test-multi-" + queues.size();
    }

    @Override
    public void start(JobRunner runner, NodeClock clock) {
        for (int i = 0; i < queues.size(); i++) {
            var queue = queues.get(i);
            Thread thread = Thread.ofPlatform().name("test-dispatcher-" + i).start(() -> {
                while (!stopNow) {
                    Job job;
                    try {
                        job = queue.poll(5, TimeUnit.MILLISECONDS);
                    } catch (InterruptedException e) {
                        return;
                    }
                    if (job != null) {
                        runner.run(job, clock.nanoTime());
                    } else if (!accepting) {
                        return;
                    }
                }
            });
            threads.add(thread);
        }
    }

    @Override
    public boolean submit(Job job) {
        if (!accepting) {
            return false;
        }
        job.place(Math.floorMod(placement.applyAsInt(job), queues.size()), job.sequence());
        var queue = queues.get(job.dispatcherId());
        queue.offer(job);
        return accepting || !queue.remove(job);
    }

    @Override
    public List<Job> shutdown(long timeoutNs) {
        accepting = false;
        long deadline = System.nanoTime() + timeoutNs;
        try {
            for (Thread thread : threads) {
                thread.join(Math.max(1, TimeUnit.NANOSECONDS.toMillis(deadline - System.nanoTime())));
            }
            stopNow = true;
            for (Thread thread : threads) {
                thread.join(2_000);
            }
        } catch (InterruptedException e) {
            Thread.currentThread().interrupt();
        }
        List<Job> unrun = new ArrayList<>();
        queues.forEach(queue -> queue.drainTo(unrun));
        return unrun;
    }
}
