package io.etherware.core.kernel.internal;

import io.etherware.core.message.Message;
import io.etherware.core.message.Profile;
import io.etherware.core.scheduler.Job;
import java.util.ArrayList;
import java.util.List;
import java.util.concurrent.atomic.AtomicBoolean;
import java.util.concurrent.atomic.AtomicInteger;
import java.util.concurrent.atomic.AtomicLong;
import java.util.concurrent.locks.ReentrantLock;
import java.util.function.Consumer;

/**
 * The ordering of a component that arrives by migration ({@link KernelCore#addHeld}): its source
 * forwards to {@link #arrival}; until the admission, and then while a penned job remains, the
 * other messages for it are <em>penned</em>, because whatever comes through the source was sent
 * before what comes here directly. Before the admission a penned job is not submitted at all but
 * <em>deferred</em>: kept here and submitted at the admission, after every forwarded job, so
 * that it follows them under any scheduler (the real-time one orders by a key taken at the
 * submission before the sequence). After it, while a penned job remains, a new one is still
 * penned by its sequence ({@link Delivery#PEN_OFFSET}), which puts it behind the deferred ones
 * under a scheduler whose urgency is the sequence; under one that orders by the submission time,
 * being submitted later does. The admission waits for the number of messages the source
 * says it forwarded, since its request may overtake some of them on the way; the source sends to
 * the component's own profile from that count on, so once that many are in, the arrival profile
 * has served its turn and is unregistered.
 *
 * <p>If the component leaves before its admission (removed, relocated onward), {@link #flush}
 * submits the deferred jobs, which then follow it as its kept ones do; at close, {@link #drain}
 * gives them up to be counted as discarded.
 *
 * <p>Thread-safety: senders call {@link #pens}, {@link #defer} and {@link #arrived}, the
 * component's owner {@link #leftPenned}, the management service {@link #admitAfter}. Deferral
 * takes the pen's lock for an append (only until the deferral ends: afterwards {@link #defer}
 * reads a volatile flag), and a flush only to take a batch; the rest is lock-free.
 */
final class ArrivalPen {

    private final Profile arrival;
    /** Releases the component's gate, once. */
    private final Runnable release;
    /** Unregisters the arrival profile, once every message the source sent to it is in. */
    private final Runnable retire;
    /** Submits a deferred job to the scheduler (or counts it discarded if refused). */
    private final Consumer<Job> submit;
    private final Object lock = new Object();
    /** Held by the one thread flushing. */
    private final ReentrantLock flushing = new ReentrantLock();
    /** Penned jobs kept until the deferral ends, in the order they were made; guarded by lock. */
    private List<Job> deferred = new ArrayList<>();
    /** Whether penned jobs are kept here; false once the admission (or a leave) submitted them. */
    private volatile boolean deferring = true;
    private final AtomicBoolean admission = new AtomicBoolean();
    private final AtomicBoolean retirement = new AtomicBoolean();
    private final AtomicLong arrivals = new AtomicLong();
    private final AtomicInteger penned = new AtomicInteger();
    private volatile boolean admitted;
    private volatile long admitAt = Long.MAX_VALUE;
    /** The source's count (the first admission's): until it is in, the arrival profile stays. */
    private volatile long retireAt = Long.MAX_VALUE;

    /**
     * @param release releases the component's gate, once
     * @param retire  unregisters the arrival profile, once
     * @param submit  submits a deferred job to the scheduler, accounting for a refusal
     */
    ArrivalPen(Profile arrival, Runnable release, Runnable retire, Consumer<Job> submit) {
        this.arrival = arrival;
        this.release = release;
        this.retire = retire;
        this.submit = submit;
    }

    /** The profile the source forwards to. */
    Profile arrival() {
        return arrival;
    }

    /** Whether the component was admitted: every message the source forwarded to it is in. */
    boolean isAdmitted() {
        return admitted;
    }

    /** Whether {@code message} comes to the arrival profile. */
    boolean isArrival(Message message) {
        return message.profile().equals(arrival);
    }

    /**
     * Admits once {@code forwardedCount} messages to the arrival profile have been submitted. The
     * first call gives the source's count; a later, lower one admits earlier (a forwarded message
     * refused on the way would never come), but the arrival profile stays registered until the
     * first call's count is in, so a message that was only late is still delivered.
     */
    void admitAfter(long forwardedCount) {
        if (retireAt == Long.MAX_VALUE) {
            retireAt = forwardedCount;
        }
        admitAt = Math.min(admitAt, forwardedCount);
        check(arrivals.get());
    }

    /** After a job for the arrival profile was submitted: admits if it was the last one awaited. */
    void arrived() {
        check(arrivals.incrementAndGet());
    }

    private void check(long arrived) {
        if (arrived >= retireAt && retirement.compareAndSet(false, true)) {
            retire.run(); // before the release: once admitted, nothing addresses the arrival profile
        }
        if (arrived >= admitAt && admission.compareAndSet(false, true)) {
            flush(); // behind every forwarded job: all of them were submitted before this
            admitted = true;
            release.run();
        }
    }

    /**
     * For a penned job just made ({@link #pens} said so): keeps it until the admission (true), or
     * false if the deferral has ended and the caller submits it as usual.
     */
    boolean defer(Job job) {
        if (!deferring) {
            return false;
        }
        synchronized (lock) {
            if (!deferring) {
                return false;
            }
            deferred.add(job);
            return true;
        }
    }

    /**
     * Ends the deferral: submits the deferred jobs in the order they were made. At the admission,
     * and when the component is removed or relocated before it; idempotent. The jobs are submitted
     * outside the pen's lock, batch by batch, so that a sender deferring meanwhile waits for no
     * submission; its job joins the next batch, and the deferral ends only when a batch comes out
     * empty, so a sender whose job is not deferred submits it after all of these. One flush at a
     * time.
     */
    void flush() {
        flushing.lock();
        try {
            while (true) {
                List<Job> due;
                synchronized (lock) {
                    if (!deferring) {
                        return;
                    }
                    if (deferred.isEmpty()) {
                        deferring = false;
                        deferred = List.of();
                        return;
                    }
                    due = deferred;
                    deferred = new ArrayList<>();
                }
                due.forEach(submit);
            }
        } finally {
            flushing.unlock();
        }
    }

    /** At close, after the dispatchers stopped: ends the deferral and returns the deferred jobs. */
    List<Job> drain() {
        synchronized (lock) {
            List<Job> left = deferred;
            deferred = List.of();
            deferring = false;
            return left;
        }
    }

    /** For a job about to be made: whether it is penned (it then counts until it has run). */
    boolean pens(Message message) {
        if (isArrival(message)) {
            return false;
        }
        if (!admitted) {
            penned.incrementAndGet();
            return true;
        }
        // Admitted: keep penning while penned jobs wait, so a sender's later message stays behind.
        while (true) {
            int now = penned.get();
            if (now == 0) {
                return false;
            }
            if (penned.compareAndSet(now, now + 1)) {
                return true;
            }
        }
    }

    /** A penned job ran or was forwarded. */
    void leftPenned() {
        penned.decrementAndGet();
    }
}
