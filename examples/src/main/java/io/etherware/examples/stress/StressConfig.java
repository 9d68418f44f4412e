package io.etherware.examples.stress;

import io.etherware.examples.scenario.PlantWiring;
import io.etherware.rt.platform.CpuSet;
import java.nio.file.Path;
import java.util.Objects;

/**
 * Settings of the stress scenario (paper Section VI-B). Immutable; validated at construction,
 * messages name the field, the value and the allowed range.
 *
 * @param durationNs        length of each run (both runs have it)
 * @param periodNs          the controller's Tick period (the paper: 15 ms)
 * @param stressEveryNs     the stressing task's Tick period (the paper: 5 s)
 * @param stressWorkNs      how long each activation computes (the paper: about 1 s)
 * @param firstStressNs     when the first stress Tick comes, after the board starts
 * @param loadThreads       ordinary threads that load the cores and allocate (0: none)
 * @param initialTheta2Rad  where the pendulum starts, off upright
 * @param out               where the CSV, plots and table go
 * @param baudRate          the serial link's rate to the DSP board (the paper: 115200); the board's
 *                          cycle and the proxy's reply timeout scale with it ({@link PlantWiring})
 * @param realtimeCpus      the CPU partition's real-time CPUs (every real-time thread there, every
 *                          other thread elsewhere), or {@link CpuSet#inherit()} for no partition
 */
public record StressConfig(long durationNs, long periodNs, long stressEveryNs, long stressWorkNs, long firstStressNs,
        int loadThreads, double initialTheta2Rad, Path out, int baudRate, CpuSet realtimeCpus) {

    /** 20 s per run: four stress activations, enough to see both outcomes. */
    public static final long DEFAULT_DURATION_NS = 20_000_000_000L;
    /** The paper's 15 ms control period. */
    public static final long DEFAULT_PERIOD_NS = 15_000_000L;
    /** The paper's stress period: every 5 s. */
    public static final long DEFAULT_STRESS_EVERY_NS = 5_000_000_000L;
    /** The paper's stress work: about 1 s. */
    public static final long DEFAULT_STRESS_WORK_NS = 1_000_000_000L;
    /** The first stress at 2 s, once the loop has settled. */
    public static final long DEFAULT_FIRST_STRESS_NS = 2_000_000_000L;
    /** Start 0.02 rad off upright, a visible but gentle disturbance. */
    public static final double DEFAULT_INITIAL_THETA2_RAD = 0.02;
    /** Longest run accepted: an hour. */
    public static final long MAX_DURATION_NS = 3_600_000_000_000L;

    public StressConfig {
        Objects.requireNonNull(out, "out");
        Objects.requireNonNull(realtimeCpus, "realtimeCpus");
        if (durationNs < 1_000_000_000L || durationNs > MAX_DURATION_NS) {
            throw new IllegalArgumentException("durationNs=" + durationNs + ": must be within 1 s .. 1 h");
        }
        if (periodNs < 1_000_000L || periodNs > 1_000_000_000L) {
            throw new IllegalArgumentException("periodNs=" + periodNs + ": must be within 1 ms .. 1 s");
        }
        if (stressEveryNs < periodNs) {
            throw new IllegalArgumentException("stressEveryNs=" + stressEveryNs + ": must be >= the control period "
                    + periodNs);
        }
        if (stressWorkNs <= 0 || stressWorkNs >= stressEveryNs || stressWorkNs > 10_000_000_000L) {
            throw new IllegalArgumentException("stressWorkNs=" + stressWorkNs
                    + ": must be > 0, below stressEveryNs=" + stressEveryNs + " and at most 10 s");
        }
        if (firstStressNs < 0) {
            throw new IllegalArgumentException("firstStressNs=" + firstStressNs + ": must be >= 0");
        }
        if (loadThreads < 0 || loadThreads > 256) {
            throw new IllegalArgumentException("loadThreads=" + loadThreads + ": must be within 0..256");
        }
        PlantWiring.requireBaudRate(baudRate);
        if (!(Math.abs(initialTheta2Rad) < 0.3)) {
            throw new IllegalArgumentException("initialTheta2Rad=" + initialTheta2Rad
                    + ": must be within ±0.3 rad (the controller balances, it does not swing up)");
        }
    }

    /** The defaults above, one load thread per core, writing to {@code out}. */
    public static StressConfig defaults(Path out) {
        return new StressConfig(DEFAULT_DURATION_NS, DEFAULT_PERIOD_NS, DEFAULT_STRESS_EVERY_NS,
                DEFAULT_STRESS_WORK_NS, DEFAULT_FIRST_STRESS_NS, Runtime.getRuntime().availableProcessors(),
                DEFAULT_INITIAL_THETA2_RAD, out, PlantWiring.DEFAULT_BAUD_RATE, CpuSet.inherit());
    }

    /** A copy with another run length. */
    public StressConfig withDurationNs(long nanos) {
        return new StressConfig(nanos, periodNs, stressEveryNs, stressWorkNs, firstStressNs, loadThreads,
                initialTheta2Rad, out, baudRate, realtimeCpus);
    }

    /** A copy with another control period. */
    public StressConfig withPeriodNs(long nanos) {
        return new StressConfig(durationNs, nanos, stressEveryNs, stressWorkNs, firstStressNs, loadThreads,
                initialTheta2Rad, out, baudRate, realtimeCpus);
    }

    /** A copy with another stress period and work. */
    public StressConfig withStress(long everyNs, long workNs) {
        return new StressConfig(durationNs, periodNs, everyNs, workNs, firstStressNs, loadThreads, initialTheta2Rad,
                out, baudRate, realtimeCpus);
    }

    /** A copy with the first stress Tick at another time after the board starts. */
    public StressConfig withFirstStressNs(long nanos) {
        return new StressConfig(durationNs, periodNs, stressEveryNs, stressWorkNs, nanos, loadThreads,
                initialTheta2Rad, out, baudRate, realtimeCpus);
    }

    /** A copy with another number of load threads. */
    public StressConfig withLoadThreads(int threads) {
        return new StressConfig(durationNs, periodNs, stressEveryNs, stressWorkNs, firstStressNs, threads,
                initialTheta2Rad, out, baudRate, realtimeCpus);
    }

    /** A copy with another serial line rate. */
    public StressConfig withBaudRate(int bitsPerSecond) {
        return new StressConfig(durationNs, periodNs, stressEveryNs, stressWorkNs, firstStressNs, loadThreads,
                initialTheta2Rad, out, bitsPerSecond, realtimeCpus);
    }

    /** A copy with the CPUs partitioned: real-time threads on {@code cpus} (inherit: no partition). */
    public StressConfig withRealtimeCpus(CpuSet cpus) {
        return new StressConfig(durationNs, periodNs, stressEveryNs, stressWorkNs, firstStressNs, loadThreads,
                initialTheta2Rad, out, baudRate, cpus);
    }
}
