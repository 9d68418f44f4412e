package io.etherware.services.network.internal;

import java.util.concurrent.locks.Condition;
import java.util.concurrent.locks.ReentrantLock;

/**
 * Who owns a lane's active connection's output: the writer thread for a turn, or a sender writing
 * one message directly (see {@link Link#enqueue}); at most one at a time. The writer waits for a
 * direct write to give the output back, and only then is it woken: waking an idle writer after
 * every direct write would cost a thread switch per message.
 *
 * <p>Locking: guarded by its link's lock, given with the link's work condition to the constructor;
 * {@link #release} takes that lock, everything else is called with it held.
 */
final class OutputToken {

    private final ReentrantLock lock;
    private final Condition work;
    /** Someone (the writer thread, or a sender writing directly) owns the active connection's output. */
    private volatile boolean held;
    /** The writer has work but waits for a direct write to give the output back. */
    private boolean writerWaits;

    OutputToken(ReentrantLock lock, Condition work) {
        this.lock = lock;
        this.work = work;
    }

    /** Whether someone owns the output (lock held). */
    boolean isHeld() {
        return held;
    }

    /** The caller owns the output now, if {@code taken} (lock held). */
    void hold(boolean taken) {
        held = taken;
    }

    /** The writer waits until the owner gives the output back (lock held). */
    void await() throws InterruptedException {
        writerWaits = true;
        work.await();
    }

    /** Whoever owned the output gives it back; a writer waiting for it may take its turn. */
    void release() {
        lock.lock();
        try {
            held = false;
            if (writerWaits) {
                writerWaits = false;
                work.signalAll();
            }
        } finally {
            lock.unlock();
        }
    }
}
