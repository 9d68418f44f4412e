package io.etherware.rt.scheduling;

import io.etherware.core.scheduler.Job;
import io.etherware.core.scheduler.JobRunner;
import io.etherware.core.scheduler.Scheduler;
import java.util.ArrayList;
import java.util.Collections;
import java.util.List;
import java.util.Map;
import java.util.PriorityQueue;
import java.util.concurrent.ConcurrentHashMap;
import java.util.concurrent.atomic.AtomicLong;

/**
 * The kernel's side of the Scheduler SPI, reduced to what scheduling tests need: one message at a
 * time per component (design decision 3). A job for a busy component is parked with it and
 * handed back through {@link Scheduler#submit}, reserved, when the component frees up, the most
 * urgent first by {@link Scheduler#urgency()}. Lets scheduler tests and the harness measure the
 * scheduler alone; the {@code Node...Test}s use the real kernel.
 */
final class FakeKernel implements JobRunner {

    /** A component's message handler, called on the dispatcher thread. */
    interface Handler {
        void onMessage(Job job, long startNs) throws Exception;
    }

    private static final class Guard {
        final PriorityQueue<Job> waiting;
        boolean busy;
        Job reservedFor;

        Guard(java.util.Comparator<Job> urgency) {
            waiting = new PriorityQueue<>(urgency);
        }
    }

    private final Map<String, Handler> handlers = new ConcurrentHashMap<>();
    private final Map<Object, Guard> guards = new ConcurrentHashMap<>();
    private final List<Job> ran = Collections.synchronizedList(new ArrayList<>());
    private final boolean recordOrder;
    private final AtomicLong failures = new AtomicLong();
    private volatile Scheduler scheduler;

    /** Records the order jobs ran in, for {@link #ran()}. */
    FakeKernel() {
        this(true);
    }

    /**
     * @param recordOrder false for long runs (the harness): the record is one list shared by all
     *                    dispatchers and grows without bound
     */
    FakeKernel(boolean recordOrder) {
        this.recordOrder = recordOrder;
    }

    FakeKernel on(String component, Handler handler) {
        handlers.put(component, handler);
        return this;
    }

    void bind(Scheduler newScheduler) {
        this.scheduler = newScheduler;
    }

    /** The jobs run, in the order they started. */
    List<Job> ran() {
        synchronized (ran) {
            return List.copyOf(ran);
        }
    }

    long failures() {
        return failures.get();
    }

    @Override
    public boolean run(Job job, long nowNs) {
        Guard guard = guards.computeIfAbsent(job.target(), target -> new Guard(scheduler.urgency()));
        synchronized (guard) {
            if (job.isReserved() && guard.reservedFor == job) {
                guard.reservedFor = null;
            } else if (guard.busy || guard.reservedFor != null) {
                guard.waiting.add(job);
                return false;
            }
            guard.busy = true;
        }
        if (recordOrder) {
            ran.add(job);
        }
        try {
            handlers.get(job.targetName()).onMessage(job, nowNs);
        } catch (Exception e) {
            failures.incrementAndGet();
        } finally {
            Job next;
            synchronized (guard) {
                guard.busy = false;
                next = guard.waiting.poll();
                if (next != null) {
                    next.reserve();
                    guard.reservedFor = next;
                }
            }
            if (next != null) {
                scheduler.submit(next);
            }
        }
        return true;
    }
}
