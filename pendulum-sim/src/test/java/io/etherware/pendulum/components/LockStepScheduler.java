package io.etherware.pendulum.components;

import io.etherware.core.scheduler.Job;
import io.etherware.core.scheduler.JobRunner;
import io.etherware.core.scheduler.Scheduler;
import io.etherware.core.time.NodeClock;
import java.util.ArrayList;
import java.util.List;
import java.util.concurrent.ConcurrentLinkedQueue;
import java.util.concurrent.ExecutionException;
import java.util.concurrent.ExecutorService;
import java.util.concurrent.Executors;
import java.util.concurrent.TimeUnit;
import java.util.concurrent.TimeoutException;

/**
 * Test scheduler for lock-step runs through a real kernel: jobs queue in arrival order and run
 * only when the test says so, on one dispatcher thread of their own (so the test thread stays a
 * non-dispatcher and may call the node's blocking management methods between steps). With a
 * {@code LockStepClock} as the node clock the run is deterministic: a job's serial waits advance
 * simulated time, and nothing runs while the test moves the clock.
 */
final class LockStepScheduler implements Scheduler {

    /** A step that runs more jobs than this is looping. */
    private static final int MAX_JOBS_PER_STEP = 10_000;

    private final ConcurrentLinkedQueue<Job> queue = new ConcurrentLinkedQueue<>();
    private final ExecutorService dispatcher = Executors.newSingleThreadExecutor(runnable -> {
        Thread thread = new Thread(runnable, "lockstep-dispatcher");
        thread.setDaemon(true);
        return thread;
    });
    private volatile JobRunner runner;
    private volatile NodeClock clock;
    private volatile boolean shut;

    @Override
    public String name() {
        return "lock-step";
    }

    @Override
    public void start(JobRunner jobRunner, NodeClock nodeClock) {
        this.runner = jobRunner;
        this.clock = nodeClock;
    }

    @Override
    public boolean submit(Job job) {
        if (shut) {
            return false;
        }
        job.place(0, job.sequence());
        queue.add(job);
        return true;
    }

    /** Runs queued jobs, and the jobs they cause, until none is left; returns how many ran. */
    int runUntilIdle() {
        return onDispatcher(() -> {
            int ran = 0;
            Job job;
            while ((job = queue.poll()) != null) {
                if (++ran > MAX_JOBS_PER_STEP) {
                    throw new AssertionError("more than " + MAX_JOBS_PER_STEP + " jobs in one step: a message loop?");
                }
                runner.run(job, clock.nanoTime());
            }
            return ran;
        });
    }

    /** Runs the oldest queued job only. */
    void runOne() {
        onDispatcher(() -> {
            Job job = queue.poll();
            if (job == null) {
                throw new AssertionError("no job queued");
            }
            runner.run(job, clock.nanoTime());
            return 1;
        });
    }

    int queued() {
        return queue.size();
    }

    private int onDispatcher(java.util.concurrent.Callable<Integer> step) {
        try {
            return dispatcher.submit(step).get(30, TimeUnit.SECONDS);
        } catch (InterruptedException e) {
            Thread.currentThread().interrupt();
            throw new AssertionError("interrupted", e);
        } catch (ExecutionException e) {
            throw new AssertionError("a lock-step step failed", e.getCause());
        } catch (TimeoutException e) {
            throw new AssertionError("a lock-step step did not finish within 30 s", e);
        }
    }

    @Override
    public List<Job> shutdown(long timeoutNs) {
        shut = true;
        dispatcher.shutdownNow();
        List<Job> unrun = new ArrayList<>(queue);
        queue.clear();
        return unrun;
    }
}
