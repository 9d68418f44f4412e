package io.etherware.core.scheduler;

import java.lang.invoke.MethodHandles;
import java.lang.invoke.VarHandle;

/**
 * The recycled jobs of one sending thread (see {@link Job#pooled} and {@link Job#recycle()}).
 *
 * <p>Jobs are made on the sending thread and finish on a dispatcher, so a pool has two lists: a
 * free list only its thread touches, and a returned list that any thread pushes onto with one CAS
 * (a Treiber stack) and that its thread takes whole with one swap when the free list is empty.
 * Taking the whole list, never one node, keeps the stack free of the ABA problem; a preempted
 * pusher delays nobody.
 *
 * <p>Bounded without counting what is out: each job pushed records its depth in the returned list,
 * and a job that would go deeper than {@link #CAPACITY} is not kept (left to the garbage
 * collector). The free list is a former returned list, so a pool holds at most twice
 * {@link #CAPACITY} jobs, whatever burst its thread once sent. A job that never comes back
 * (discarded, forwarded by a relocation, or run by a scheduler that does not recycle) costs the
 * pool nothing: when both lists are empty, the thread makes a new job. Virtual threads take no
 * pool. A pool dies with its thread: jobs still out then return to a pool nobody takes from, and
 * are collected with it.
 *
 * <p>Thread-safety: {@link #take} on the owning thread only (through the thread-local);
 * {@link #giveBack} from any thread. The swap's acquire pairs with the push's release, so the
 * cleared fields of a returned job are visible to the thread that takes it.
 */
final class JobPool {

    /** Jobs a pool's returned list keeps at most: 64 KiB of jobs. */
    static final int CAPACITY = 1024;

    private static final ThreadLocal<JobPool> POOLS = ThreadLocal.withInitial(JobPool::new);
    private static final VarHandle RETURNED;

    static {
        try {
            RETURNED = MethodHandles.lookup().findVarHandle(JobPool.class, "returned", Job.class);
        } catch (ReflectiveOperationException e) {
            throw new ExceptionInInitializerError(e);
        }
    }

    /** Owner only. */
    private Job free;
    /** Pushed by any thread, taken whole by the owner. */
    @SuppressWarnings("unused") // through RETURNED
    private volatile Job returned;

    private JobPool() {
    }

    /**
     * On any thread: a job of the calling thread's pool, free or new; one of no pool on a virtual
     * thread (those are many and short-lived: a pool each would outweigh the jobs).
     */
    static Job take() {
        if (Thread.currentThread().isVirtual()) {
            return new Job((JobPool) null);
        }
        return POOLS.get().takeOwn();
    }

    private Job takeOwn() {
        Job job = free;
        if (job == null) {
            job = (Job) RETURNED.getAndSet(this, (Job) null);
            if (job == null) {
                return new Job(this);
            }
        }
        free = job.poolNext;
        job.poolNext = null;
        return job;
    }

    /** Any thread: a recycled job of this pool comes back, unless the returned list is full. */
    void giveBack(Job job) {
        Job head;
        do {
            head = returned;
            int depth = head == null ? 1 : head.poolDepth + 1;
            if (depth > CAPACITY) {
                return; // full: left to the garbage collector
            }
            job.poolNext = head;
            job.poolDepth = depth;
        } while (!RETURNED.compareAndSet(this, head, job));
    }
}
