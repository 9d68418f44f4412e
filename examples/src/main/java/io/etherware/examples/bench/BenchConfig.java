package io.etherware.examples.bench;

import io.etherware.rt.scheduling.RealtimeScheduler;
import io.etherware.rt.scheduling.RealtimeSchedulerConfig;
import java.util.concurrent.TimeUnit;

/**
 * How long and how much each section of the bench measures. Immutable; validated when built.
 * Defaults: {@link #full(double)}; {@link #quick()} is the about-30-seconds smoke run.
 *
 * @param periodicNs          each periodic-lateness row (section 1)
 * @param dispatchNs          each dispatch-latency row (section 2)
 * @param throughputNs        each throughput row (section 3)
 * @param warmupNs            warm-up before each timed row of sections 1-3
 * @param codecOps            timed calls per codec row (section 4)
 * @param roundTrips          round trips per loopback row (section 5)
 * @param upgradeRepetitions  upgrades measured (section 6)
 * @param priority            SCHED_FIFO priority of the periodic threads (Notifier, executor, cyclictest)
 * @param realtimeBursts      whether saturating bursts (the upgrade's message chain, a few ms each) may
 *                            run on SCHED_FIFO dispatchers; false in the smoke run, which runs in the test suite
 * @param holdCpuLatency      whether the bench's real-time nodes hold {@code /dev/cpu_dma_latency} at 0 (as the
 *                            bench itself does then), so every row runs in the same CPU-latency state
 */
public record BenchConfig(long periodicNs, long dispatchNs, long throughputNs, long warmupNs, int codecOps,
                          int roundTrips, int upgradeRepetitions, int priority, boolean realtimeBursts,
                          boolean holdCpuLatency) {

    /** The real-time period of sections 1 and 2: 1 kHz. */
    public static final long PERIOD_NS = TimeUnit.MILLISECONDS.toNanos(1);
    /** Default length of a periodic row in the full run, seconds. */
    public static final double DEFAULT_PERIODIC_S = 60;
    /** Default SCHED_FIFO priority: the Notifier's (two above the HIGH dispatcher's 80, above the network's 81). */
    public static final int DEFAULT_PRIORITY = 82;

    /** Validates every field. */
    public BenchConfig {
        requireAtLeast("periodicNs", periodicNs, TimeUnit.MILLISECONDS.toNanos(100));
        requireAtLeast("dispatchNs", dispatchNs, TimeUnit.MILLISECONDS.toNanos(100));
        requireAtLeast("throughputNs", throughputNs, TimeUnit.MILLISECONDS.toNanos(100));
        requireAtLeast("warmupNs", warmupNs, 0);
        requireAtLeast("codecOps", codecOps, 100);
        requireAtLeast("roundTrips", roundTrips, 100);
        requireAtLeast("upgradeRepetitions", upgradeRepetitions, 5);
        if (priority < 1 || priority > 98) {
            throw new IllegalArgumentException("priority=" + priority + ": must be 1..98 (SCHED_FIFO; 99 is the kernel's)");
        }
    }

    private static void requireAtLeast(String field, long value, long min) {
        if (value < min) {
            throw new IllegalArgumentException(field + "=" + value + ": must be >= " + min);
        }
    }

    /** The full run: {@code periodicS} per periodic row, 10 s per dispatch row, 3 s per throughput row. */
    public static BenchConfig full(double periodicS) {
        return new BenchConfig(secondsToNs(periodicS), TimeUnit.SECONDS.toNanos(10), TimeUnit.SECONDS.toNanos(3),
                TimeUnit.SECONDS.toNanos(2), 200_000, 30_000, 200, DEFAULT_PRIORITY, true, true);
    }

    /** The smoke run: about 30 s in all, enough samples for every row to be sane, not for its figures. */
    public static BenchConfig quick() {
        return new BenchConfig(TimeUnit.MILLISECONDS.toNanos(1500), TimeUnit.MILLISECONDS.toNanos(1000),
                TimeUnit.MILLISECONDS.toNanos(500), TimeUnit.MILLISECONDS.toNanos(300), 5_000, 2_000, 20,
                DEFAULT_PRIORITY, false, true);
    }

    /** This configuration with another number of upgrades in section 6. */
    public BenchConfig withUpgradeRepetitions(int repetitions) {
        return new BenchConfig(periodicNs, dispatchNs, throughputNs, warmupNs, codecOps, roundTrips, repetitions,
                priority, realtimeBursts, holdCpuLatency);
    }

    /** This configuration with the nodes' CPU latency request on or off. */
    public BenchConfig withHoldCpuLatency(boolean hold) {
        return new BenchConfig(periodicNs, dispatchNs, throughputNs, warmupNs, codecOps, roundTrips,
                upgradeRepetitions, priority, realtimeBursts, hold);
    }

    /** A Table II scheduler (the defaults) holding the CPU latency as this configuration says. */
    RealtimeScheduler realtimeScheduler() {
        return realtimeScheduler(RealtimeSchedulerConfig.builder());
    }

    /** A scheduler built from {@code builder}, holding the CPU latency as this configuration says. */
    RealtimeScheduler realtimeScheduler(RealtimeSchedulerConfig.Builder builder) {
        return new RealtimeScheduler(builder.holdCpuLatency(holdCpuLatency).build());
    }

    private static long secondsToNs(double seconds) {
        if (!(seconds >= 0.1)) {
            throw new IllegalArgumentException("periodicS=" + seconds + ": must be >= 0.1 s");
        }
        return Math.round(seconds * 1e9);
    }
}
