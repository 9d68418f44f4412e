package io.etherware.rt.scheduling;

import io.etherware.rt.platform.CpuSet;
import java.util.Objects;
import java.util.regex.Pattern;

/**
 * Configuration of a {@link RealtimeScheduler}, validated when built (a bad value fails fast with
 * {@code field=value} and the fix).
 *
 * <p>Defaults, in one place:
 * <ul>
 *   <li>{@code name} = {@code rt}: thread names are {@code rt-dispatcher-<id>};</li>
 *   <li>{@code threadSchedulingRule} = {@link ThreadSchedulingRule#tableII()}: dispatcher 0
 *       SCHED_OTHER, 1..3 SCHED_FIFO 80/70/60. Without the privilege for SCHED_FIFO the scheduler
 *       warns once with the fix and runs at ordinary priorities;</li>
 *   <li>{@code placementRule} = {@link CriticalityDeadlinePlacement} (the paper's Algorithm 1);</li>
 *   <li>{@code admissionMode} = {@link AdmissionMode#WARN};</li>
 *   <li>{@code lockMemory} = false (when true, {@code mlockall(MCL_CURRENT|MCL_FUTURE)} at start);</li>
 *   <li>{@code priorityInheritance} = true: while a job waits for its component, the dispatcher
 *       running that component is raised to the waiting job's dispatcher priority;</li>
 *   <li>{@code deadlineMissHandler} = {@link DeadlineMissHandler#NONE};</li>
 *   <li>{@code holdCpuLatency} = true: while the scheduler runs and has a real-time dispatcher, it
 *       holds {@code /dev/cpu_dma_latency} at 0 ({@link io.etherware.rt.platform.CpuLatencyHold}),
 *       as {@code cyclictest} does; refused (no permission), it warns once and runs on;</li>
 *   <li>{@code realtimeCpus} = {@link CpuSet#inherit()}: no CPU partition. Named CPUs partition the
 *       JVM at start ({@link io.etherware.rt.platform.CpuPartition}): the real-time threads there,
 *       every other thread of the JVM on the remaining CPUs.</li>
 * </ul>
 *
 * @param name                 prefix of thread names and the scheduler's {@code name()}
 * @param threadSchedulingRule the dispatchers and their OS priorities (TSR)
 * @param placementRule        the scheduling policy (JPR)
 * @param admissionMode        what to do with a declared stream that breaks a bound
 * @param lockMemory           whether to lock the process's memory at start
 * @param priorityInheritance  whether to raise a component's running dispatcher for a waiting job
 * @param deadlineMissHandler  called on a deadline miss, on the dispatcher thread
 * @param holdCpuLatency       whether to keep the CPUs out of deep idle states while running
 * @param realtimeCpus         the CPUs of the JVM's real-time threads, or inherit for no partition
 */
public record RealtimeSchedulerConfig(String name, ThreadSchedulingRule threadSchedulingRule,
                                      JobPlacementRule placementRule, AdmissionMode admissionMode,
                                      boolean lockMemory, boolean priorityInheritance,
                                      DeadlineMissHandler deadlineMissHandler, boolean holdCpuLatency,
                                      CpuSet realtimeCpus) {

    private static final Pattern NAME = Pattern.compile("[A-Za-z0-9_.-]{1,32}");

    public RealtimeSchedulerConfig {
        Objects.requireNonNull(name, "name");
        Objects.requireNonNull(threadSchedulingRule, "threadSchedulingRule");
        Objects.requireNonNull(placementRule, "placementRule");
        Objects.requireNonNull(admissionMode, "admissionMode");
        Objects.requireNonNull(deadlineMissHandler, "deadlineMissHandler");
        Objects.requireNonNull(realtimeCpus, "realtimeCpus");
        if (!NAME.matcher(name).matches()) {
            throw new IllegalArgumentException("name='" + name + "' must be 1..32 of [A-Za-z0-9_.-]");
        }
        if (placementRule.dispatchersRequired() > threadSchedulingRule.size()) {
            throw new IllegalArgumentException("placementRule=" + placementRule + " places jobs on "
                    + placementRule.dispatchersRequired() + " dispatchers, but threadSchedulingRule="
                    + threadSchedulingRule + " has " + threadSchedulingRule.size()
                    + "; give the rule at least " + placementRule.dispatchersRequired() + " dispatchers");
        }
    }

    /** The defaults listed above. */
    public static RealtimeSchedulerConfig defaults() {
        return builder().build();
    }

    public static Builder builder() {
        return new Builder();
    }

    /** A builder starting from this configuration. */
    public Builder toBuilder() {
        return new Builder().name(name).threadSchedulingRule(threadSchedulingRule).placementRule(placementRule)
                .admissionMode(admissionMode).lockMemory(lockMemory).priorityInheritance(priorityInheritance)
                .deadlineMissHandler(deadlineMissHandler).holdCpuLatency(holdCpuLatency).realtimeCpus(realtimeCpus);
    }

    /** Builds a {@link RealtimeSchedulerConfig}; not thread-safe, {@link #build()} validates. */
    public static final class Builder {
        private String name = "rt";
        private ThreadSchedulingRule threadSchedulingRule = ThreadSchedulingRule.tableII();
        private JobPlacementRule placementRule = new CriticalityDeadlinePlacement();
        private AdmissionMode admissionMode = AdmissionMode.WARN;
        private boolean lockMemory;
        private boolean priorityInheritance = true;
        private DeadlineMissHandler deadlineMissHandler = DeadlineMissHandler.NONE;
        private boolean holdCpuLatency = true;
        private CpuSet realtimeCpus = CpuSet.inherit();

        private Builder() {
        }

        public Builder name(String newName) {
            this.name = newName;
            return this;
        }

        public Builder threadSchedulingRule(ThreadSchedulingRule rule) {
            this.threadSchedulingRule = rule;
            return this;
        }

        public Builder placementRule(JobPlacementRule rule) {
            this.placementRule = rule;
            return this;
        }

        public Builder admissionMode(AdmissionMode mode) {
            this.admissionMode = mode;
            return this;
        }

        public Builder lockMemory(boolean lock) {
            this.lockMemory = lock;
            return this;
        }

        public Builder priorityInheritance(boolean inherit) {
            this.priorityInheritance = inherit;
            return this;
        }

        public Builder deadlineMissHandler(DeadlineMissHandler handler) {
            this.deadlineMissHandler = handler;
            return this;
        }

        /** Whether to hold the CPUs out of deep idle states while a real-time dispatcher runs. */
        public Builder holdCpuLatency(boolean hold) {
            this.holdCpuLatency = hold;
            return this;
        }

        /**
         * Partitions the JVM's CPUs at start: the real-time dispatchers (and every thread that later
         * asks the platform for a real-time policy on inherited CPUs: Notifier, network threads) on
         * {@code cpus}, every other thread on the rest. {@link CpuSet#inherit()}: no partition.
         */
        public Builder realtimeCpus(CpuSet cpus) {
            this.realtimeCpus = cpus;
            return this;
        }

        public RealtimeSchedulerConfig build() {
            return new RealtimeSchedulerConfig(name, threadSchedulingRule, placementRule, admissionMode, lockMemory,
                    priorityInheritance, deadlineMissHandler, holdCpuLatency, realtimeCpus);
        }
    }
}
