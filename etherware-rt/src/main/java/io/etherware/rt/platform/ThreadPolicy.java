package io.etherware.rt.platform;

import java.util.Objects;

/**
 * A thread's scheduling policy and static priority: what a dispatcher asks of the OS, and what the
 * OS reports it granted. Immutable.
 *
 * <p>The record checks only what is always wrong ({@link SchedulingPolicy#OTHER} with a priority,
 * a negative priority); the real-time range (1..99 on Linux) is the OS's to enforce, so a request
 * outside it reaches the OS and comes back refused with {@code EINVAL}. Configuration
 * ({@code ThreadSchedulingRule}) validates the range up front.
 *
 * @param policy   the scheduling policy
 * @param priority the static priority: 0 for {@link SchedulingPolicy#OTHER}, 1..99 for the
 *                 real-time policies on Linux (higher runs first)
 */
public record ThreadPolicy(SchedulingPolicy policy, int priority) {

    /** SCHED_OTHER, the JVM's ordinary threads. */
    public static final ThreadPolicy NON_REALTIME = new ThreadPolicy(SchedulingPolicy.OTHER, 0);

    /**
     * Rejects what no OS grants.
     *
     * @throws NullPointerException     when {@code policy} is null
     * @throws IllegalArgumentException when {@code priority} is negative, or not 0 with
     *                                  {@link SchedulingPolicy#OTHER}
     */
    public ThreadPolicy {
        Objects.requireNonNull(policy, "policy");
        if (policy == SchedulingPolicy.OTHER && priority != 0) {
            throw new IllegalArgumentException("priority=" + priority
                    + " is not allowed with SCHED_OTHER: its static priority is always 0");
        }
        if (priority < 0) {
            throw new IllegalArgumentException("priority=" + priority + " must not be negative");
        }
    }

    /**
     * SCHED_FIFO at a priority.
     *
     * @param priority the static priority, 1..99 on Linux (higher runs first); a value outside
     *                 that range is refused by the OS when requested, not here
     * @return the policy
     * @throws IllegalArgumentException when {@code priority} is negative
     */
    public static ThreadPolicy fifo(int priority) {
        return new ThreadPolicy(SchedulingPolicy.FIFO, priority);
    }

    /**
     * SCHED_RR at a priority.
     *
     * @param priority the static priority, 1..99 on Linux (higher runs first); a value outside
     *                 that range is refused by the OS when requested, not here
     * @return the policy
     * @throws IllegalArgumentException when {@code priority} is negative
     */
    public static ThreadPolicy roundRobin(int priority) {
        return new ThreadPolicy(SchedulingPolicy.RR, priority);
    }

    /**
     * Whether this asks for a real-time policy.
     *
     * @return true for SCHED_FIFO and SCHED_RR
     */
    public boolean isRealtime() {
        return policy.isRealtime();
    }

    /** {@code SCHED_FIFO/80}, or {@code SCHED_OTHER}. */
    @Override
    public String toString() {
        return policy.isRealtime() ? policy.osName() + "/" + priority : policy.osName();
    }
}
