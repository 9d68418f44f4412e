package io.etherware.pendulum.serial;

import java.lang.foreign.Arena;
import java.lang.foreign.FunctionDescriptor;
import java.lang.foreign.Linker;
import java.lang.foreign.MemoryLayout;
import java.lang.foreign.MemorySegment;
import java.lang.foreign.ValueLayout;
import java.lang.invoke.MethodHandle;
import java.lang.invoke.VarHandle;
import java.util.concurrent.ThreadFactory;
import org.slf4j.Logger;
import org.slf4j.LoggerFactory;

/**
 * Test helper: puts the calling thread under SCHED_FIFO at a given priority through
 * {@code sched_setscheduler(0, …)} (Linux applies it to the calling thread only), or warns once
 * and runs on. Only for threads that sleep between short bursts of work — never a spinning
 * thread. The real-time module provides the production version of this; pendulum-sim does not
 * depend on it, so its tests use this one (public for the component tests).
 */
public final class RealTimePriority {

    private static final Logger LOG = LoggerFactory.getLogger(RealTimePriority.class);
    private static final int SCHED_FIFO = 1;
    private static final Linker LINKER = Linker.nativeLinker();
    private static final MemoryLayout ERRNO_STATE = Linker.Option.captureStateLayout();
    private static final VarHandle ERRNO = ERRNO_STATE.varHandle(
            MemoryLayout.PathElement.groupElement("errno"));
    private static final MethodHandle SCHED_SETSCHEDULER = LINKER.downcallHandle(
            LINKER.defaultLookup().find("sched_setscheduler").orElseThrow(),
            FunctionDescriptor.of(ValueLayout.JAVA_INT, ValueLayout.JAVA_INT, ValueLayout.JAVA_INT,
                    ValueLayout.ADDRESS),
            Linker.Option.captureCallState("errno"));

    private RealTimePriority() {}

    /** Tries SCHED_FIFO at {@code priority} for the calling thread; returns whether it worked. */
    public static boolean requestFifo(int priority) {
        try (Arena arena = Arena.ofConfined()) {
            MemorySegment errno = arena.allocate(ERRNO_STATE);
            MemorySegment param = arena.allocate(ValueLayout.JAVA_INT);
            param.set(ValueLayout.JAVA_INT, 0, priority);
            int rc = (int) SCHED_SETSCHEDULER.invokeExact(errno, 0, SCHED_FIFO, param);
            if (rc != 0) {
                LOG.warn("SCHED_FIFO {} refused for {} (errno {}); running at normal priority",
                        priority, Thread.currentThread().getName(), (int) ERRNO.get(errno, 0L));
                return false;
            }
            return true;
        } catch (Throwable t) {
            LOG.warn("SCHED_FIFO unavailable: {}", t.toString());
            return false;
        }
    }

    /** A factory of daemon threads that ask for SCHED_FIFO at {@code priority} as they start. */
    public static ThreadFactory fifoThreads(String name, int priority) {
        return runnable -> {
            Thread thread = new Thread(() -> {
                requestFifo(priority);
                runnable.run();
            }, name);
            thread.setDaemon(true);
            return thread;
        };
    }
}
