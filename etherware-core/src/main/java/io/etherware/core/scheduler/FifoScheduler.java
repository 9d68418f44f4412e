package io.etherware.core.scheduler;

import io.etherware.core.time.NodeClock;
import java.util.ArrayList;
import java.util.List;
import java.util.Objects;
import java.util.concurrent.ConcurrentLinkedQueue;
import java.util.concurrent.TimeUnit;
import java.util.concurrent.locks.LockSupport;
import org.slf4j.Logger;
import org.slf4j.LoggerFactory;

/**
 * The original Etherware's Dispatcher (paper Section III-A): one platform thread takes jobs from
 * one FIFO queue and runs them one by one, whatever their QoS. It is the baseline the real-time
 * scheduler is measured against (design decision 5).
 *
 * <p>The queue is lock-free; the dispatcher parks when it is empty and a submitter unparks it only
 * when it sleeps. Urgency is arrival order.
 *
 * <p>Thread-safety: {@link #submit} from any thread, including the dispatcher; {@link #start} and
 * {@link #shutdown} once each, from one thread.
 */
public final class FifoScheduler implements Scheduler {

    private static final Logger log = LoggerFactory.getLogger(FifoScheduler.class);
    /** A parked dispatcher re-checks its queue at least this often, as a safety net. */
    private static final long PARK_NS = TimeUnit.MILLISECONDS.toNanos(100);
    /** How long shutdown waits for a handler that does not return, after the drain timeout. */
    private static final long STOP_WAIT_MS = 2_000;

    private final ConcurrentLinkedQueue<Job> queue = new ConcurrentLinkedQueue<>();
    private final String threadName;
    private volatile boolean accepting = true;
    private volatile boolean stopNow;
    private volatile boolean sleeping;
    private volatile Thread dispatcher;

    /** A scheduler whose thread is named {@code etherware-fifo@<nodeId>}. */
    public FifoScheduler() {
        this("etherware-fifo");
    }

    /**
     * A scheduler whose dispatcher thread has the given name, followed by {@code @<nodeId>} when a
     * node runs it ({@link JobRunner#nodeId()}).
     *
     * @param threadName the dispatcher thread's name, as thread dumps and logs show it
     */
    public FifoScheduler(String threadName) {
        this.threadName = Objects.requireNonNull(threadName, "threadName");
    }

    @Override
    public String name() {
        return "fifo";
    }

    @Override
    public void start(JobRunner runner, NodeClock clock) {
        Objects.requireNonNull(runner, "runner");
        Objects.requireNonNull(clock, "clock");
        if (dispatcher != null) {
            throw new IllegalStateException("FifoScheduler.start() works once");
        }
        String node = runner.nodeId();
        String name = node == null || node.isEmpty() ? threadName : threadName + "@" + node;
        Thread thread = Thread.ofPlatform().name(name).unstarted(() -> dispatch(runner, clock));
        dispatcher = thread;
        thread.start();
    }

    private void dispatch(JobRunner runner, NodeClock clock) {
        while (!stopNow) {
            Job job = queue.poll();
            if (job != null) {
                try {
                    runner.run(job, clock.nanoTime());
                } catch (RuntimeException | Error e) {
                    // The kernel supervises component failures; this is a kernel bug. Keep going.
                    log.error("dispatcher {}: job {} escaped the kernel's supervision", threadName, job, e);
                }
                continue;
            }
            if (!accepting) {
                return; // drained
            }
            sleeping = true;
            // Re-check after announcing sleep: a submitter offers, then reads 'sleeping' (both
            // volatile), so either it sees us sleeping and unparks, or we see its job here.
            if (queue.isEmpty() && accepting && !stopNow) {
                LockSupport.parkNanos(this, PARK_NS);
            }
            sleeping = false;
        }
    }

    @Override
    public boolean submit(Job job) {
        if (!accepting) {
            return false;
        }
        job.place(0, job.sequence());
        queue.offer(job);
        if (!accepting && queue.remove(job)) {
            // Shutdown began between the check and the offer and nobody took the job: refuse it,
            // so it is counted by the caller and never left behind in a dead queue.
            return false;
        }
        if (sleeping) {
            LockSupport.unpark(dispatcher);
        }
        return true;
    }

    @Override
    public List<Job> shutdown(long timeoutNs) {
        accepting = false;
        Thread thread = dispatcher;
        List<Job> unrun = new ArrayList<>();
        if (thread != null) {
            LockSupport.unpark(thread);
            try {
                thread.join(Math.max(1, TimeUnit.NANOSECONDS.toMillis(timeoutNs)));
                if (thread.isAlive()) {
                    stopNow = true;
                    LockSupport.unpark(thread);
                    thread.join(STOP_WAIT_MS);
                }
            } catch (InterruptedException e) {
                stopNow = true;
                Thread.currentThread().interrupt();
            }
            if (thread.isAlive()) {
                log.error("dispatcher {} did not stop: a handler has run for more than {} ms", threadName,
                        TimeUnit.NANOSECONDS.toMillis(timeoutNs) + STOP_WAIT_MS);
            }
        }
        for (Job job; (job = queue.poll()) != null; ) {
            unrun.add(job);
        }
        return unrun;
    }
}
