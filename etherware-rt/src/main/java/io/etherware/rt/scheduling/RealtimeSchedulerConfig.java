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
 *   <li>{@code name} = {@code rt}: thread names are {@code rt-dispatcher-<id>@<nodeId>}
 *       (without {@code @<nodeId>} when no node runs the scheduler);</li>
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

    /**
     * Validates the configuration.
     *
     * @throws NullPointerException     when a component other than a {@code boolean} is null
     * @throws IllegalArgumentException when {@code name} is not 1..32 of {@code [A-Za-z0-9_.-]}, or
     *                                  {@code placementRule} needs more dispatchers than
     *                                  {@code threadSchedulingRule} has
     */
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

    /**
     * The defaults listed above.
     *
     * @return a configuration with every default
     */
    public static RealtimeSchedulerConfig defaults() {
        return builder().build();
    }

    /**
     * A builder starting from the defaults listed above.
     *
     * @return a new builder
     */
    public static Builder builder() {
        return new Builder();
    }

    /**
     * A builder starting from this configuration, to change a few fields.
     *
     * @return a new builder holding every field of this configuration
     */
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

        /**
         * Sets the name; default {@code rt}.
         *
         * @param newName 1..32 of {@code [A-Za-z0-9_.-]}: the prefix of the dispatcher threads'
         *                names and the scheduler's {@code name()}
         * @return this builder
         */
        public Builder name(String newName) {
            this.name = newName;
            return this;
        }

        /**
         * Sets the dispatchers and their OS priorities; default {@link ThreadSchedulingRule#tableII()}.
         *
         * @param rule the rule; it needs at least as many dispatchers as the placement rule uses
         * @return this builder
         */
        public Builder threadSchedulingRule(ThreadSchedulingRule rule) {
            this.threadSchedulingRule = rule;
            return this;
        }

        /**
         * Sets the scheduling policy; default {@link CriticalityDeadlinePlacement}.
         *
         * @param rule the rule; it is called concurrently on submitting threads
         * @return this builder
         */
        public Builder placementRule(JobPlacementRule rule) {
            this.placementRule = rule;
            return this;
        }

        /**
         * Sets what admission control does with a stream that breaks a bound; default
         * {@link AdmissionMode#WARN}.
         *
         * @param mode the mode
         * @return this builder
         */
        public Builder admissionMode(AdmissionMode mode) {
            this.admissionMode = mode;
            return this;
        }

        /**
         * Sets whether the scheduler locks the process's memory at start; default false.
         *
         * @param lock true for {@code mlockall(MCL_CURRENT|MCL_FUTURE)} at start (see
         *             {@link io.etherware.rt.platform.Platform#lockMemory()} for sizing the JVM)
         * @return this builder
         */
        public Builder lockMemory(boolean lock) {
            this.lockMemory = lock;
            return this;
        }

        /**
         * Sets priority inheritance; default true.
         *
         * @param inherit true to raise the dispatcher running a component to the priority of a job
         *                waiting for that component
         * @return this builder
         */
        public Builder priorityInheritance(boolean inherit) {
            this.priorityInheritance = inherit;
            return this;
        }

        /**
         * Sets the deadline-miss handler; default {@link DeadlineMissHandler#NONE}.
         *
         * @param handler called on the dispatcher thread that ran a late job; must not block
         * @return this builder
         */
        public Builder deadlineMissHandler(DeadlineMissHandler handler) {
            this.deadlineMissHandler = handler;
            return this;
        }

        /**
         * Whether to hold the CPUs out of deep idle states while a real-time dispatcher runs;
         * default true.
         *
         * @param hold true to hold {@code /dev/cpu_dma_latency} at 0 while the scheduler runs, when it
         *             has a real-time dispatcher
         * @return this builder
         */
        public Builder holdCpuLatency(boolean hold) {
            this.holdCpuLatency = hold;
            return this;
        }

        /**
         * Partitions the JVM's CPUs at start: the real-time dispatchers (and every thread that later
         * asks the platform for a real-time policy on inherited CPUs: Notifier, network threads) on
         * {@code cpus}, every other thread on the rest. {@link CpuSet#inherit()}: no partition.
         *
         * @param cpus the real-time CPUs, or {@link CpuSet#inherit()} (the default) for no partition
         * @return this builder
         */
        public Builder realtimeCpus(CpuSet cpus) {
            this.realtimeCpus = cpus;
            return this;
        }

        /**
         * Builds and validates the configuration.
         *
         * @return the configuration
         * @throws NullPointerException     when an object field was set to null
         * @throws IllegalArgumentException when the name is malformed or the placement rule needs
         *                                  more dispatchers than the thread scheduling rule has
         */
        public RealtimeSchedulerConfig build() {
            return new RealtimeSchedulerConfig(name, threadSchedulingRule, placementRule, admissionMode, lockMemory,
                    priorityInheritance, deadlineMissHandler, holdCpuLatency, realtimeCpus);
        }
    }
}
