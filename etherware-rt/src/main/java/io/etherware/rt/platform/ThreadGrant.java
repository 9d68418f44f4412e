package io.etherware.rt.platform;

import java.util.List;
import java.util.Objects;

/**
 * What one thread asked of the OS and what the OS granted, read back from the OS after the
 * request (not from our own bookkeeping). Immutable.
 *
 * @param threadName    the Java thread's name
 * @param osThreadId    the kernel thread id, or -1 when unknown
 * @param requested     the requested policy and priority
 * @param granted       the policy and priority the OS reports for the thread
 * @param requestedCpus the requested affinity
 * @param grantedCpus   the affinity the OS reports, or {@link CpuSet#inherit()} when unknown
 * @param refusals      what was refused, empty when everything was granted
 */
public record ThreadGrant(String threadName, int osThreadId, ThreadPolicy requested, ThreadPolicy granted,
                          CpuSet requestedCpus, CpuSet grantedCpus, List<PlatformRefusal> refusals) {

    /**
     * Keeps an unmodifiable copy of {@code refusals}.
     *
     * @throws NullPointerException when a component other than {@code osThreadId} is null, or
     *                              {@code refusals} holds a null
     */
    public ThreadGrant {
        Objects.requireNonNull(threadName, "threadName");
        Objects.requireNonNull(requested, "requested");
        Objects.requireNonNull(granted, "granted");
        Objects.requireNonNull(requestedCpus, "requestedCpus");
        Objects.requireNonNull(grantedCpus, "grantedCpus");
        refusals = List.copyOf(refusals);
    }

    /**
     * Whether the OS granted the policy and priority asked for; the affinity is not compared.
     *
     * @return true when {@code granted} equals {@code requested}
     */
    public boolean isPolicyGranted() {
        return requested.equals(granted);
    }

    /**
     * This grant as one report line.
     *
     * @return e.g. {@code rt-dispatcher-1 tid=4711: requested SCHED_FIFO/80 cpus=inherit, granted
     *         SCHED_OTHER cpus=0-1 [thread priority SCHED_FIFO/80 refused: EPERM ...]}; the
     *         refusals only when there are some
     */
    public String toLine() {
        var line = new StringBuilder(threadName).append(" tid=").append(osThreadId)
                .append(": requested ").append(requested).append(" cpus=").append(requestedCpus)
                .append(", granted ").append(granted).append(" cpus=").append(grantedCpus);
        if (!refusals.isEmpty()) {
            line.append(' ').append(refusals);
        }
        return line.toString();
    }
}
