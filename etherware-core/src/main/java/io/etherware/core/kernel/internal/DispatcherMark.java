package io.etherware.core.kernel.internal;

/**
 * Marks the threads that run jobs, whichever scheduler owns them, so that blocking calls (which
 * would wait for a delivery the same thread must make) can refuse to run there.
 *
 * <p>Thread-safety: each thread reads and writes only its own mark.
 */
public final class DispatcherMark {

    private static final ThreadLocal<Boolean> MARK = new ThreadLocal<>();

    private DispatcherMark() {
    }

    /** Marks the calling thread; called by the kernel's job runner, idempotent. */
    static void markCurrentThread() {
        if (MARK.get() == null) {
            MARK.set(Boolean.TRUE);
        }
    }

    /** Whether the calling thread has run jobs for a kernel. */
    public static boolean isDispatcherThread() {
        return MARK.get() != null;
    }

    /**
     * Throws if the calling thread is a dispatcher.
     *
     * @param what the blocking call, for the message, e.g. {@code requestBlocking}
     */
    public static void requireNotDispatcher(String what, String instead) {
        if (isDispatcherThread()) {
            throw new IllegalStateException(what + " was called on dispatcher thread '" + Thread.currentThread().getName()
                    + "': it would block the dispatcher that must deliver what it waits for (deadlock). " + instead);
        }
    }
}
