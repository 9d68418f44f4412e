package io.etherware.core.testing;

import io.etherware.core.scheduler.Job;
import io.etherware.core.scheduler.JobRunner;
import io.etherware.core.scheduler.Scheduler;
import io.etherware.core.time.NodeClock;
import java.util.ArrayList;
import java.util.List;
import java.util.concurrent.ExecutionException;
import java.util.concurrent.ExecutorService;
import java.util.concurrent.Executors;
import java.util.concurrent.Future;
import java.util.concurrent.LinkedBlockingDeque;
import java.util.concurrent.TimeUnit;
import java.util.concurrent.TimeoutException;
import java.util.function.ToIntFunction;

/**
 * A scheduler driven by the test: jobs queue per dispatcher until the test takes one and runs it
 * on that dispatcher's thread (one single-thread executor per dispatcher), so races between
 * dispatchers can be staged step by step.
 */
public final class ManualScheduler implements Scheduler {

    private final List<LinkedBlockingDeque<Job>> queues = new ArrayList<>();
    private final List<ExecutorService> dispatchers = new ArrayList<>();
    private final ToIntFunction<Job> placement;
    private volatile JobRunner runner;
    private volatile NodeClock clock;

    public ManualScheduler(int dispatcherCount, ToIntFunction<Job> placement) {
        for (int i = 0; i < dispatcherCount; i++) {
            queues.add(new LinkedBlockingDeque<>());
            int id = i;
            dispatchers.add(Executors.newSingleThreadExecutor(r -> new Thread(r, "manual-dispatcher-" + id)));
        }
        this.placement = placement;
    }

    @Override
    public String name() {
        return "manual";
    }

    @Override
    public void start(JobRunner jobRunner, NodeClock nodeClock) {
        this.runner = jobRunner;
        this.clock = nodeClock;
    }

    @Override
    public boolean submit(Job job) {
        job.place(placement.applyAsInt(job), job.sequence());
        queues.get(job.dispatcherId()).add(job);
        return true;
    }

    /** Takes the next job of a dispatcher's queue, waiting up to 10 s for one. */
    public Job take(int dispatcher) throws InterruptedException {
        Job job = queues.get(dispatcher).poll(10, TimeUnit.SECONDS);
        if (job == null) {
            throw new AssertionError("no job for dispatcher " + dispatcher);
        }
        return job;
    }

    public int queued(int dispatcher) {
        return queues.get(dispatcher).size();
    }

    /** Starts running {@code job} on the dispatcher's thread. */
    public Future<Boolean> runAsync(int dispatcher, Job job) {
        return dispatchers.get(dispatcher).submit(() -> runner.run(job, clock.nanoTime()));
    }

    /** Runs {@code job} on the dispatcher's thread and returns what the runner returned. */
    public boolean run(int dispatcher, Job job) throws InterruptedException, ExecutionException, TimeoutException {
        return runAsync(dispatcher, job).get(10, TimeUnit.SECONDS);
    }

    @Override
    public List<Job> shutdown(long timeoutNs) {
        dispatchers.forEach(ExecutorService::shutdownNow);
        List<Job> unrun = new ArrayList<>();
        queues.forEach(queue -> queue.drainTo(unrun));
        return unrun;
    }
}
