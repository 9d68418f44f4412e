package io.etherware.services.management;

import io.etherware.services.management.ManagementFailure.Reason;
import java.util.concurrent.Executor;
import java.util.concurrent.ExecutorService;
import java.util.concurrent.Executors;
import java.util.concurrent.RejectedExecutionException;
import java.util.concurrent.atomic.AtomicBoolean;
import java.util.concurrent.atomic.AtomicInteger;
import java.util.concurrent.atomic.LongAdder;
import java.util.function.BiConsumer;
import java.util.function.Consumer;

/**
 * One of a management service's threads, with its bounded queue: what is handed to it runs one at
 * a time in arrival order, at most {@link ManagementConfig#maxQueuedOperations()} waiting besides
 * the one in progress, and a request beyond that is answered {@link Reason#BUSY} at once
 * (counted). The service has two: the worker (upgrades' loading and answering, migrations away
 * from this node) and the steps thread (PREPARE steps of migrations into this node). Each lives as
 * long as its service object; the thread is made when the service starts ({@link #start}) and
 * shut down when it stops, and the count of requests in the queue carries over.
 *
 * <p>Thread-safety: {@link #start} and {@link #shutdown} on the kernel's lifecycle calls, the rest
 * from any thread after {@link #start}; takes no lock (the queue's count is atomic).
 */
final class OperationQueue {

    private final String threadName;
    /** Requests handed to the thread and not yet answered or done (the one in progress included). */
    private final AtomicInteger in = new AtomicInteger();
    private final String nodeId;
    private final ManagementConfig config;
    /** Counts the requests answered BUSY. */
    private final LongAdder busy;
    private ExecutorService pool;
    private Executor continuations;

    /**
     * @param threadName the thread's name
     * @param nodeId     the node, for answers
     * @param config     where the bound comes from
     * @param busy       counts the requests answered BUSY
     */
    OperationQueue(String threadName, String nodeId, ManagementConfig config, LongAdder busy) {
        this.threadName = threadName;
        this.nodeId = nodeId;
        this.config = config;
        this.busy = busy;
    }

    /** The service starts: a new thread serves the queue from now on. */
    void start() {
        this.pool = Executors.newSingleThreadExecutor(Thread.ofPlatform().daemon().name(threadName).factory());
        this.continuations = inlineWhenRefused(pool);
    }

    /** Runs a task on {@code pool}, or where it completes if the pool has stopped. */
    private static Executor inlineWhenRefused(ExecutorService pool) {
        // After onStop, an operation in flight still answers: on the thread that completes it.
        return task -> {
            try {
                pool.execute(task);
            } catch (RejectedExecutionException refused) {
                task.run();
            }
        };
    }

    /**
     * Gives back a request's place in its queue, once: before its answer is sent, so that whoever
     * asks again on that answer finds the place free.
     */
    static final class Permit {
        private final AtomicInteger in;
        private final AtomicBoolean released = new AtomicBoolean();

        Permit(AtomicInteger in) {
            this.in = in;
        }

        void release() {
            if (released.compareAndSet(false, true)) {
                in.decrementAndGet();
            }
        }
    }

    /**
     * Hands {@code task} to the thread if fewer than {@link ManagementConfig#maxQueuedOperations()}
     * wait besides the one in progress; otherwise, or if the service stops, answers the request
     * through {@code failure} (BUSY with the bound, or SERVICE_FAILED). The task releases its
     * permit before it answers.
     */
    void submit(Consumer<Permit> task, BiConsumer<Reason, String> failure) {
        if (in.incrementAndGet() > 1 + config.maxQueuedOperations()) {
            in.decrementAndGet();
            busy.increment();
            failure.accept(Reason.BUSY, "the management service of node '" + nodeId + "' has "
                    + config.maxQueuedOperations() + " operations waiting behind the one in progress"
                    + " (maxQueuedOperations); nothing was done: ask again later");
            return;
        }
        var permit = new Permit(in);
        try {
            pool.execute(() -> {
                try {
                    task.accept(permit);
                } finally {
                    permit.release();
                }
            });
        } catch (RejectedExecutionException e) {
            permit.release();
            failure.accept(Reason.SERVICE_FAILED, "the management service of node '" + nodeId
                    + "' is stopping");
        }
    }

    /**
     * Where answers that wait are assembled: on the thread made by the latest {@link #start}, or
     * where they complete once it stopped.
     */
    Executor continuations() {
        return continuations;
    }

    /** The service stops: the thread ends after what it has (continuations then run inline). */
    void shutdown() {
        pool.shutdown();
    }
}
