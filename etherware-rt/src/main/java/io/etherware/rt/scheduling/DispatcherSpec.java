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

    public DispatcherSpec {
        Objects.requireNonNull(policy, "policy");
        Objects.requireNonNull(cpus, "cpus");
    }

    /** An ordinary (SCHED_OTHER) dispatcher on any CPU. */
    public static DispatcherSpec nonRealtime() {
        return new DispatcherSpec(ThreadPolicy.NON_REALTIME, CpuSet.inherit());
    }

    /** A SCHED_FIFO dispatcher at {@code priority} on any CPU. */
    public static DispatcherSpec fifo(int priority) {
        return new DispatcherSpec(ThreadPolicy.fifo(priority), CpuSet.inherit());
    }

    /** This dispatcher on {@code newCpus}. */
    public DispatcherSpec on(CpuSet newCpus) {
        return new DispatcherSpec(policy, newCpus);
    }

    @Override
    public String toString() {
        return cpus.isInherit() ? policy.toString() : policy + "@cpus=" + cpus;
    }
}
