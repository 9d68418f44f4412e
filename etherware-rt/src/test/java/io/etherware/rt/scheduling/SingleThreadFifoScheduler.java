package io.etherware.rt.scheduling;

import io.etherware.core.scheduler.Job;
import io.etherware.core.scheduler.JobRunner;
import io.etherware.core.scheduler.Scheduler;
import io.etherware.core.time.NodeClock;
import java.util.ArrayList;
import java.util.List;
import java.util.concurrent.LinkedBlockingQueue;
import java.util.concurrent.TimeUnit;

/**
 * The original Etherware's dispatching, minimal: one ordinary thread, one FIFO queue. The baseline
 * in tests and the harness until the kernel's FifoScheduler is on this branch.
 */
final class SingleThreadFifoScheduler implements Scheduler {

    private final LinkedBlockingQueue<Job> queue = new LinkedBlockingQueue<>();
    private volatile boolean stopped;
    private Thread thread;

    @Override
    public String name() {
        return "fifo-baseline";
    }

    @Override
    public void start(JobRunner runner, NodeClock clock) {
        thread = Thread.ofPlatform().name("fifo-baseline").daemon(true).start(() -> {
            while (!stopped) {
                try {
                    Job job = queue.take();
                    runner.run(job, clock.nanoTime());
                } catch (InterruptedException e) {
                    return;
                }
            }
        });
    }

    @Override
    public boolean submit(Job job) {
        if (stopped) {
            return false;
        }
        job.place(0, 0);
        return queue.add(job);
    }

    @Override
    public List<Job> shutdown(long timeoutNs) {
        long deadlineNs = System.nanoTime() + timeoutNs;
        while (!queue.isEmpty() && System.nanoTime() < deadlineNs) {
            try {
                Thread.sleep(1);
            } catch (InterruptedException e) {
                Thread.currentThread().interrupt();
                break;
            }
        }
        stopped = true;
        thread.interrupt();
        try {
            thread.join(TimeUnit.SECONDS.toMillis(1));
        } catch (InterruptedException e) {
            Thread.currentThread().interrupt();
        }
        var left = new ArrayList<Job>();
        queue.drainTo(left);
        return left;
    }
}
