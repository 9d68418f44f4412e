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
 * urgency, see {@link Delivery#PEN_OFFSET}), because whatever comes through the source was sent
 * before what comes here directly. The admission waits for the number of messages the source
 * says it forwarded, since its request may overtake some of them on the way; the source sends to
 * the component's own profile from that count on, so once that many are in, the arrival profile
 * has served its turn and is unregistered.
 *
 * <p>Thread-safety: senders call {@link #pens} and {@link #arrived}, the component's owner
 * {@link #leftPenned}, the management service {@link #admitAfter}; all lock-free.
 */
final class ArrivalPen {

    private final Profile arrival;
    /** Releases the component's gate, once. */
    private final Runnable release;
    /** Unregisters the arrival profile, once every message the source sent to it is in. */
    private final Runnable retire;
    private final AtomicBoolean admission = new AtomicBoolean();
    private final AtomicBoolean retirement = new AtomicBoolean();
    private final AtomicLong arrivals = new AtomicLong();
    private final AtomicInteger penned = new AtomicInteger();
    private volatile boolean admitted;
    private volatile long admitAt = Long.MAX_VALUE;
    /** The source's count (the first admission's): until it is in, the arrival profile stays. */
    private volatile long retireAt = Long.MAX_VALUE;

    ArrivalPen(Profile arrival, Runnable release, Runnable retire) {
        this.arrival = arrival;
        this.release = release;
        this.retire = retire;
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
