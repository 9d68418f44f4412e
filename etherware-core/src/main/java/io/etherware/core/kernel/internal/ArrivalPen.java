package io.etherware.core.kernel.internal;

import io.etherware.core.message.Message;
import io.etherware.core.message.Profile;
import java.util.concurrent.atomic.AtomicBoolean;
import java.util.concurrent.atomic.AtomicInteger;
import java.util.concurrent.atomic.AtomicLong;

/**
 * The ordering of a component that arrives by migration ({@link KernelCore#addHeld}): its source
 * forwards to {@link #arrival}; until the admission, and then while a penned job remains, the
 * other messages for it are <em>penned</em> (their jobs sort after every forwarded one of the same
 * urgency, see {@link KernelCore#PEN_OFFSET}), because whatever comes through the source was sent
 * before what comes here directly. The admission waits for the number of messages the source
 * says it forwarded, since its request may overtake some of them on the way; the source sends to
 * the component's own profile from that count on, so at the admission the arrival profile has
 * served its turn and is unregistered.
 *
 * <p>Thread-safety: senders call {@link #pens} and {@link #arrived}, the component's owner
 * {@link #leftPenned}, the management service {@link #admitAfter}; all lock-free.
 */
final class ArrivalPen {

    private final Profile arrival;
    /** Releases the component's gate, once. */
    private final Runnable release;
    private final AtomicBoolean admission = new AtomicBoolean();
    private final AtomicLong arrivals = new AtomicLong();
    private final AtomicInteger penned = new AtomicInteger();
    private volatile boolean admitted;
    private volatile long admitAt = Long.MAX_VALUE;

    ArrivalPen(Profile arrival, Runnable release) {
        this.arrival = arrival;
        this.release = release;
    }

    /** The profile the source forwards to. */
    Profile arrival() {
        return arrival;
    }

    /** Whether {@code message} comes to the arrival profile. */
    boolean isArrival(Message message) {
        return message.profile().equals(arrival);
    }

    /** Admits once {@code forwardedCount} messages to the arrival profile have been submitted. */
    void admitAfter(long forwardedCount) {
        admitAt = forwardedCount;
        if (arrivals.get() >= forwardedCount) {
            admitOnce();
        }
    }

    /** After a job for the arrival profile was submitted: admits if it was the last one awaited. */
    void arrived() {
        if (arrivals.incrementAndGet() >= admitAt) {
            admitOnce();
        }
    }

    private void admitOnce() {
        if (admission.compareAndSet(false, true)) {
            admitted = true;
            release.run();
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
