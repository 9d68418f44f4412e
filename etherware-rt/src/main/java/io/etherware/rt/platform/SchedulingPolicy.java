package io.etherware.rt.platform;

/**
 * A Linux thread scheduling policy, as set by {@code sched_setscheduler(2)}. Immutable.
 *
 * <p>{@link #FIFO} and {@link #RR} are the real-time policies: a runnable thread of a higher
 * real-time priority always runs before any lower one and before every {@link #OTHER} thread.
 */
public enum SchedulingPolicy {
    /** {@code SCHED_OTHER}: the ordinary time-shared policy; its static priority is always 0. */
    OTHER("SCHED_OTHER"),
    /** {@code SCHED_FIFO}: real-time, runs until it blocks, yields or a higher priority preempts it. */
    FIFO("SCHED_FIFO"),
    /** {@code SCHED_RR}: real-time like {@link #FIFO}, with a time slice among equal priorities. */
    RR("SCHED_RR");

    private final String osName;

    SchedulingPolicy(String osName) {
        this.osName = osName;
    }

    /**
     * Whether this is a real-time policy.
     *
     * @return true for {@link #FIFO} and {@link #RR}, false for {@link #OTHER}
     */
    public boolean isRealtime() {
        return this != OTHER;
    }

    /**
     * The name the kernel documentation uses.
     *
     * @return e.g. {@code SCHED_FIFO}
     */
    public String osName() {
        return osName;
    }
}
