package io.etherware.rt.scheduling;

import io.etherware.rt.platform.CpuSet;
import io.etherware.rt.platform.ThreadPolicy;
import java.util.Objects;

/**
 * One dispatcher of a {@link ThreadSchedulingRule}: the OS policy and priority its thread asks for,
 * and optionally the CPUs it may run on. Immutable.
 *
 * @param policy the requested policy and priority; {@link ThreadPolicy#NON_REALTIME} for an
 *               ordinary thread
 * @param cpus   the requested affinity, or {@link CpuSet#inherit()}
 */
public record DispatcherSpec(ThreadPolicy policy, CpuSet cpus) {

    /**
     * A dispatcher asking for {@code policy} on {@code cpus}; the priority range is checked by the
     * {@link ThreadSchedulingRule} it goes into.
     *
     * @throws NullPointerException when {@code policy} or {@code cpus} is null
     */
    public DispatcherSpec {
        Objects.requireNonNull(policy, "policy");
        Objects.requireNonNull(cpus, "cpus");
    }

    /**
     * An ordinary (SCHED_OTHER) dispatcher on the inherited CPUs.
     *
     * @return the spec
     */
    public static DispatcherSpec nonRealtime() {
        return new DispatcherSpec(ThreadPolicy.NON_REALTIME, CpuSet.inherit());
    }

    /**
     * A SCHED_FIFO dispatcher on the inherited CPUs.
     *
     * @param priority the real-time priority, 1..99 on Linux (higher runs first)
     * @return the spec
     * @throws IllegalArgumentException when {@code priority} is negative; the rest of the range is
     *                                  checked by the {@link ThreadSchedulingRule}
     */
    public static DispatcherSpec fifo(int priority) {
        return new DispatcherSpec(ThreadPolicy.fifo(priority), CpuSet.inherit());
    }

    /**
     * This dispatcher's policy on other CPUs.
     *
     * @param newCpus the CPUs, or {@link CpuSet#inherit()}
     * @return a new spec; this one is unchanged
     */
    public DispatcherSpec on(CpuSet newCpus) {
        return new DispatcherSpec(policy, newCpus);
    }

    @Override
    public String toString() {
        return cpus.isInherit() ? policy.toString() : policy + "@cpus=" + cpus;
    }
}
