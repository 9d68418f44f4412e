package io.etherware.rt.scheduling;

import io.etherware.rt.platform.CpuSet;
import io.etherware.rt.platform.ThreadPolicy;
import java.util.ArrayList;
import java.util.Collections;
import java.util.List;
import java.util.Objects;

/**
 * The Thread Scheduling Rule (TSR) of paper Section IV-B: how many dispatchers the Dispatching
 * Module has, and each one's OS priority and CPUs. Dispatcher {@code i} is {@code dispatchers.get(i)}.
 *
 * <p>{@link #tableII()} mirrors the paper's Table II: dispatcher 0 non-real-time, dispatchers 1..3
 * real-time with descending priority. The paper's levels came from Sun Java RTS; on Linux we use
 * SCHED_FIFO {@value #HIGH_PRIORITY}/{@value #MIDDLE_PRIORITY}/{@value #LOW_PRIORITY}: above the
 * threaded interrupt handlers (priority 50 on PREEMPT_RT kernels), so a control loop is not held up
 * by unrelated device interrupts, and below 99, which the kernel keeps for its own watchdog and
 * migration threads. Real-time levels must be in 1..99.
 *
 * <p>Immutable and thread-safe.
 *
 * @param dispatchers the dispatchers, at least one
 */
public record ThreadSchedulingRule(List<DispatcherSpec> dispatchers) {

    /** Table II's dispatcher 1 (HIGH criticality). */
    public static final int HIGH_PRIORITY = 80;
    /** Table II's dispatcher 2 (MIDDLE criticality). */
    public static final int MIDDLE_PRIORITY = 70;
    /** Table II's dispatcher 3 (LOW criticality). */
    public static final int LOW_PRIORITY = 60;
    /** The lowest real-time priority Linux accepts. */
    public static final int MIN_REALTIME_PRIORITY = 1;
    /** The highest real-time priority Linux accepts. */
    public static final int MAX_REALTIME_PRIORITY = 99;
    /** More dispatchers than this is a configuration mistake, not a design. */
    public static final int MAX_DISPATCHERS = 64;

    /**
     * The policy {@code levels} real-time priorities above this rule's highest real-time dispatcher
     * (at most 99), with its policy; {@link ThreadPolicy#NON_REALTIME} when no dispatcher is
     * real-time. The node's priority map (board, Notifier, network I/O, dispatchers) is built from
     * it: network I/O one level above, the Notifier two.
     *
     * @param levels how many priority levels above, 0 or more
     * @return the policy, its priority capped at {@value #MAX_REALTIME_PRIORITY}
     * @throws IllegalArgumentException when {@code levels} is negative
     */
    public ThreadPolicy above(int levels) {
        if (levels < 0) {
            throw new IllegalArgumentException("levels=" + levels + " must be >= 0");
        }
        ThreadPolicy highest = ThreadPolicy.NON_REALTIME;
        for (DispatcherSpec spec : dispatchers) {
            ThreadPolicy policy = spec.policy();
            if (policy.isRealtime() && policy.priority() >= highest.priority()) {
                highest = policy;
            }
        }
        if (!highest.isRealtime()) {
            return ThreadPolicy.NON_REALTIME;
        }
        return new ThreadPolicy(highest.policy(), Math.min(highest.priority() + levels, MAX_REALTIME_PRIORITY));
    }

    /**
     * The policy {@code levels} real-time priorities above this rule's lowest real-time dispatcher
     * (at most 99), with its policy; {@link ThreadPolicy#NON_REALTIME} when no dispatcher is
     * real-time. The network lane that carries LOW messages runs one level above.
     *
     * @param levels how many priority levels above, 0 or more
     * @return the policy, its priority capped at {@value #MAX_REALTIME_PRIORITY}
     * @throws IllegalArgumentException when {@code levels} is negative
     */
    public ThreadPolicy aboveLowest(int levels) {
        if (levels < 0) {
            throw new IllegalArgumentException("levels=" + levels + " must be >= 0");
        }
        ThreadPolicy lowest = null;
        for (DispatcherSpec spec : dispatchers) {
            ThreadPolicy policy = spec.policy();
            if (policy.isRealtime() && (lowest == null || policy.priority() < lowest.priority())) {
                lowest = policy;
            }
        }
        return lowest == null ? ThreadPolicy.NON_REALTIME
                : new ThreadPolicy(lowest.policy(), Math.min(lowest.priority() + levels, MAX_REALTIME_PRIORITY));
    }

    /**
     * This rule with its real-time dispatchers on other CPUs; the others stay where they are.
     *
     * @param cpus the CPUs, or {@link CpuSet#inherit()}
     * @return a new rule; this one is unchanged
     */
    public ThreadSchedulingRule withRealtimeOn(CpuSet cpus) {
        Objects.requireNonNull(cpus, "cpus");
        var specs = new ArrayList<DispatcherSpec>(dispatchers.size());
        for (DispatcherSpec spec : dispatchers) {
            specs.add(spec.policy().isRealtime() ? spec.on(cpus) : spec);
        }
        return new ThreadSchedulingRule(specs);
    }

    /**
     * Validates the dispatchers and keeps an unmodifiable copy of them.
     *
     * @throws NullPointerException     when {@code dispatchers} or one of them is null
     * @throws IllegalArgumentException when there are none or more than {@value #MAX_DISPATCHERS}, or
     *                                  a real-time dispatcher's priority is outside
     *                                  {@value #MIN_REALTIME_PRIORITY}..{@value #MAX_REALTIME_PRIORITY}
     */
    public ThreadSchedulingRule {
        Objects.requireNonNull(dispatchers, "dispatchers");
        if (dispatchers.isEmpty() || dispatchers.size() > MAX_DISPATCHERS) {
            throw new IllegalArgumentException("dispatchers.size=" + dispatchers.size() + " must be in 1.."
                    + MAX_DISPATCHERS);
        }
        for (int i = 0; i < dispatchers.size(); i++) {
            DispatcherSpec spec = Objects.requireNonNull(dispatchers.get(i), "dispatchers[" + i + "]");
            ThreadPolicy policy = spec.policy();
            if (policy.isRealtime() && (policy.priority() < MIN_REALTIME_PRIORITY
                    || policy.priority() > MAX_REALTIME_PRIORITY)) {
                throw new IllegalArgumentException("dispatchers[" + i + "].priority=" + policy.priority()
                        + " must be in " + MIN_REALTIME_PRIORITY + ".." + MAX_REALTIME_PRIORITY + " for "
                        + policy.policy().osName());
            }
        }
        dispatchers = List.copyOf(dispatchers);
    }

    /**
     * The paper's Table II: dispatcher 0 SCHED_OTHER, dispatchers 1, 2, 3 SCHED_FIFO
     * {@value #HIGH_PRIORITY}, {@value #MIDDLE_PRIORITY}, {@value #LOW_PRIORITY}.
     *
     * @return the rule, all on the inherited CPUs
     */
    public static ThreadSchedulingRule tableII() {
        return new ThreadSchedulingRule(List.of(DispatcherSpec.nonRealtime(), DispatcherSpec.fifo(HIGH_PRIORITY),
                DispatcherSpec.fifo(MIDDLE_PRIORITY), DispatcherSpec.fifo(LOW_PRIORITY)));
    }

    /**
     * Ordinary dispatchers only: the Dispatching Module's structure without OS priorities.
     *
     * @param count how many dispatchers, 1..{@value #MAX_DISPATCHERS}
     * @return the rule, all SCHED_OTHER on the inherited CPUs
     * @throws IllegalArgumentException when {@code count} is out of range
     */
    public static ThreadSchedulingRule nonRealtime(int count) {
        if (count < 1) {
            throw new IllegalArgumentException("count=" + count + " must be >= 1");
        }
        return new ThreadSchedulingRule(Collections.nCopies(count, DispatcherSpec.nonRealtime()));
    }

    /**
     * The given dispatchers, in id order.
     *
     * @param dispatchers dispatcher 0 first; 1..{@value #MAX_DISPATCHERS} of them
     * @return the rule
     * @throws NullPointerException     when a dispatcher is null
     * @throws IllegalArgumentException as the canonical constructor
     */
    public static ThreadSchedulingRule of(DispatcherSpec... dispatchers) {
        return new ThreadSchedulingRule(List.of(dispatchers));
    }

    /**
     * The same dispatchers and CPUs, all SCHED_OTHER: for CPU-heavy tests and machines without
     * privileges.
     *
     * @return a new rule; this one is unchanged
     */
    public ThreadSchedulingRule withoutRealtime() {
        var copy = new ArrayList<DispatcherSpec>();
        dispatchers.forEach(spec -> copy.add(new DispatcherSpec(ThreadPolicy.NON_REALTIME, spec.cpus())));
        return new ThreadSchedulingRule(copy);
    }

    /**
     * How many dispatchers the Dispatching Module has.
     *
     * @return the number of dispatchers, 1..{@value #MAX_DISPATCHERS}
     */
    public int size() {
        return dispatchers.size();
    }

    /**
     * One dispatcher's spec.
     *
     * @param id the dispatcher, 0..{@link #size()}-1
     * @return its policy and CPUs
     * @throws IndexOutOfBoundsException when there is no such dispatcher
     */
    public DispatcherSpec dispatcher(int id) {
        return dispatchers.get(id);
    }

    /**
     * How urgent dispatcher {@code id} is relative to the others: its real-time priority, or 0 for
     * a non-real-time one. Higher runs first.
     *
     * @param id the dispatcher, 0..{@link #size()}-1
     * @return the rank, 0..{@value #MAX_REALTIME_PRIORITY}
     * @throws IndexOutOfBoundsException when there is no such dispatcher
     */
    public int rank(int id) {
        ThreadPolicy policy = dispatchers.get(id).policy();
        return policy.isRealtime() ? policy.priority() : 0;
    }

    /** {@code [0:SCHED_OTHER, 1:SCHED_FIFO/80, ...]}. */
    @Override
    public String toString() {
        var text = new StringBuilder("[");
        for (int i = 0; i < dispatchers.size(); i++) {
            text.append(i == 0 ? "" : ", ").append(i).append(':').append(dispatchers.get(i));
        }
        return text.append(']').toString();
    }
}
