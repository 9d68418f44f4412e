package io.etherware.services.notifier;

import io.etherware.core.message.Profile;
import io.etherware.core.time.Durations;
import io.etherware.rt.platform.CpuSet;
import io.etherware.rt.platform.ThreadPolicy;
import io.etherware.rt.scheduling.ThreadSchedulingRule;
import java.time.Duration;
import java.util.Objects;

/**
 * How a {@link Notifier} runs: its profile, its thread's OS policy and CPUs, and the optional spin
 * before each release. Immutable; validated when built, naming the wrong field.
 *
 * <p>Defaults ({@link #defaults()}): SCHED_FIFO {@value #DEFAULT_PRIORITY}, two levels above the
 * highest dispatcher of the paper's Table II ({@link ThreadSchedulingRule#HIGH_PRIORITY}) and one
 * above the network's threads, so a Tick is released before any component work that it activates
 * (or any message in transit) can delay it; every CPU (a CPU partition's real-time CPUs under one);
 * no spin; the last stretch before each release slept in the kernel to the release time where
 * possible.
 * The priority is a request: refused (no CAP_SYS_NICE, say), the platform warns once with the
 * errno and the fix, and the Notifier runs on at the priority it has. Use {@link #above} to sit
 * two levels above another rule, and {@link #withThreadPolicy} with
 * {@link ThreadPolicy#NON_REALTIME} to ask for nothing.
 *
 * @param profile      the profile of the Notifier's component, or null for
 *                     {@link Notifier#profileFor(String) etherware.notifier[node=&lt;nodeId&gt;]}
 * @param threadPolicy the OS policy and priority requested for the Notifier thread
 * @param cpus         the CPUs of the Notifier thread
 * @param spinNs       how long before each release the thread stops sleeping and spins on the
 *                     clock instead, in 0..{@value #MAX_SPIN_NS} (0: no spin). A spin trades CPU
 *                     for wake-up accuracy; it is bounded per release, so at real-time priority it
 *                     takes at most {@code spinNs} per release from everything else on its CPU
 * @param threadName   the Notifier thread's name, to which the Notifier adds {@code @<nodeId>}
 *                     (thread dumps then tell the Notifiers of two nodes in one JVM apart)
 * @param kernelSleep  whether the thread sleeps the last stretch before each release in the kernel
 *                     to the absolute release time ({@code clock_nanosleep(CLOCK_MONOTONIC,
 *                     TIMER_ABSTIME)}, {@link io.etherware.rt.platform.AbsoluteSleeper}) where that
 *                     call is usable (default), or only parks ({@code LockSupport.parkNanos})
 */
public record NotifierConfig(Profile profile, ThreadPolicy threadPolicy, CpuSet cpus, long spinNs,
                             String threadName, boolean kernelSleep) {

    /**
     * Default SCHED_FIFO priority: two above Table II's highest dispatcher, with the network's
     * reader and writer threads between them (the node's priority map is in the README).
     */
    public static final int DEFAULT_PRIORITY = ThreadSchedulingRule.HIGH_PRIORITY + 2;
    /** Longest allowed spin before a release: 100 µs. */
    public static final long MAX_SPIN_NS = 100_000;
    /** Default thread name. */
    public static final String DEFAULT_THREAD_NAME = "etherware-notifier";

    private static final NotifierConfig DEFAULTS = new NotifierConfig(null, ThreadPolicy.fifo(DEFAULT_PRIORITY),
            CpuSet.inherit(), 0, DEFAULT_THREAD_NAME, true);

    /**
     * Checks every field.
     *
     * @throws NullPointerException     if {@code threadPolicy}, {@code cpus} or {@code threadName} is
     *                                  null
     * @throws IllegalArgumentException if a real-time priority is outside 1..99, {@code spinNs}
     *                                  outside 0..{@value #MAX_SPIN_NS}, or {@code threadName} blank
     */
    public NotifierConfig {
        Objects.requireNonNull(threadPolicy, "threadPolicy");
        Objects.requireNonNull(cpus, "cpus");
        Objects.requireNonNull(threadName, "threadName");
        if (threadPolicy.isRealtime() && (threadPolicy.priority() < ThreadSchedulingRule.MIN_REALTIME_PRIORITY
                || threadPolicy.priority() > ThreadSchedulingRule.MAX_REALTIME_PRIORITY)) {
            throw new IllegalArgumentException("threadPolicy.priority=" + threadPolicy.priority() + " must be in "
                    + ThreadSchedulingRule.MIN_REALTIME_PRIORITY + ".." + ThreadSchedulingRule.MAX_REALTIME_PRIORITY
                    + " for " + threadPolicy.policy().osName());
        }
        if (spinNs < 0 || spinNs > MAX_SPIN_NS) {
            throw new IllegalArgumentException("spinNs=" + spinNs + " must be in 0.." + MAX_SPIN_NS
                    + " (a spin at real-time priority must be short; 0 turns it off)");
        }
        if (threadName.isBlank()) {
            throw new IllegalArgumentException("threadName='" + threadName + "' must not be blank");
        }
    }

    /**
     * The defaults: SCHED_FIFO {@value #DEFAULT_PRIORITY}, every CPU, no spin, kernel sleep where
     * usable, the node's default profile, thread {@value #DEFAULT_THREAD_NAME}.
     *
     * @return the shared default configuration
     */
    public static NotifierConfig defaults() {
        return DEFAULTS;
    }

    /**
     * The defaults, but two real-time levels above the highest dispatcher of {@code rule} (at most
     * 99), with the same policy; {@link ThreadPolicy#NON_REALTIME} when no dispatcher of the rule
     * is real-time.
     *
     * @param rule the dispatchers' scheduling rule, normally the node's scheduler's
     * @return the defaults with that thread policy
     */
    public static NotifierConfig above(ThreadSchedulingRule rule) {
        Objects.requireNonNull(rule, "rule");
        return DEFAULTS.withThreadPolicy(rule.above(2));
    }

    /**
     * This configuration under another profile.
     *
     * @param newProfile the profile of the Notifier's component and sender of its Ticks, or null
     *                   for {@link Notifier#profileFor(String)} of the node
     * @return a copy with that profile
     */
    public NotifierConfig withProfile(Profile newProfile) {
        return new NotifierConfig(newProfile, threadPolicy, cpus, spinNs, threadName, kernelSleep);
    }

    /**
     * This configuration asking for another OS policy for the Notifier thread.
     *
     * @param newThreadPolicy the policy and priority (real-time priorities 1..99), or
     *                        {@link ThreadPolicy#NON_REALTIME} to ask for nothing
     * @return a copy with that policy
     * @throws IllegalArgumentException if a real-time priority is outside 1..99
     */
    public NotifierConfig withThreadPolicy(ThreadPolicy newThreadPolicy) {
        return new NotifierConfig(profile, newThreadPolicy, cpus, spinNs, threadName, kernelSleep);
    }

    /**
     * This configuration with the Notifier thread on other CPUs.
     *
     * @param newCpus the CPUs, or {@link CpuSet#inherit()} (default) to leave the affinity as inherited
     * @return a copy with those CPUs
     */
    public NotifierConfig withCpus(CpuSet newCpus) {
        return new NotifierConfig(profile, threadPolicy, newCpus, spinNs, threadName, kernelSleep);
    }

    /**
     * This configuration spinning for the last {@code spin} before each release.
     *
     * @param spin the spin, 0..{@value #MAX_SPIN_NS} ns (zero, the default: no spin)
     * @return a copy with that spin
     * @throws IllegalArgumentException if {@code spin} is out of range
     */
    public NotifierConfig withSpin(Duration spin) {
        return new NotifierConfig(profile, threadPolicy, cpus, Durations.toNs("spin", spin), threadName, kernelSleep);
    }

    /**
     * This configuration naming the Notifier thread differently (e.g. one Notifier per node in
     * one JVM).
     *
     * @param newThreadName the name, not blank; default {@value #DEFAULT_THREAD_NAME}
     * @return a copy with that name
     * @throws IllegalArgumentException if {@code newThreadName} is blank
     */
    public NotifierConfig withThreadName(String newThreadName) {
        return new NotifierConfig(profile, threadPolicy, cpus, spinNs, newThreadName, kernelSleep);
    }

    /**
     * This configuration sleeping in the kernel to each release time or only parking.
     *
     * @param newKernelSleep true (default) to sleep the last stretch with
     *                       {@code clock_nanosleep(TIMER_ABSTIME)} where usable, false to only park
     * @return a copy with that choice
     */
    public NotifierConfig withKernelSleep(boolean newKernelSleep) {
        return new NotifierConfig(profile, threadPolicy, cpus, spinNs, threadName, newKernelSleep);
    }
}
