package io.etherware.pendulum.dsp;

import io.etherware.core.time.Durations;
import io.etherware.pendulum.plant.PendulumPlant;
import java.time.Duration;

/**
 * Settings of the simulated DSP board. Immutable and thread-safe; validated at construction,
 * messages name the field, the value and the allowed range.
 *
 * @param stepNs the board's cycle and the plant's RK4 step: once per step the board serves the
 *     serial link, checks the watchdog and integrates the plant with the held torque
 * @param countsPerRevolution encoder resolution (quadrature counts per revolution)
 * @param maxTorqueNm the motor's torque range; commands beyond it are clamped
 * @param watchdogTimeoutNs with no SET_TORQUE for this long the board cuts the motor and raises
 *     its fault flag until commands resume
 * @param maxSpinNs real-time mode only: the longest busy-wait before a step, after sleeping
 *     (0: sleep only; never spin at real-time priority on a shared box)
 */
public record DspBoardConfig(
        long stepNs,
        int countsPerRevolution,
        double maxTorqueNm,
        long watchdogTimeoutNs,
        long maxSpinNs) {

    /** 4096 counts per revolution. */
    public static final int DEFAULT_COUNTS_PER_REVOLUTION = 4096;
    /**
     * 0.5 N·m, the range of a small direct-drive DC motor: over four times the peak torque either
     * gain set asks for when recovering from 0.05 rad (V1 0.06 N·m, V2 0.11 N·m).
     */
    public static final double DEFAULT_MAX_TORQUE_NM = 0.5;
    /** 100 ms without a command cuts the motor. */
    public static final long DEFAULT_WATCHDOG_TIMEOUT_NS = 100_000_000L;
    /** At most 1 ms of busy-waiting. */
    public static final long MAX_SPIN_LIMIT_NS = 1_000_000L;

    /**
     * Validates every field.
     *
     * @throws IllegalArgumentException when {@code stepNs} is outside [10 µs, 10 ms],
     *     {@code countsPerRevolution} below 4, {@code maxTorqueNm} not finite and positive,
     *     {@code watchdogTimeoutNs} shorter than a step, or {@code maxSpinNs} outside
     *     [0, {@value #MAX_SPIN_LIMIT_NS}]
     */
    public DspBoardConfig {
        if (stepNs < 10_000L || stepNs > 10_000_000L) {
            throw new IllegalArgumentException("stepNs=" + stepNs
                    + ": must be within [10000, 10000000] (10 µs to 10 ms)");
        }
        if (countsPerRevolution < 4) {
            throw new IllegalArgumentException("countsPerRevolution=" + countsPerRevolution
                    + ": must be >= 4");
        }
        if (!(maxTorqueNm > 0) || !Double.isFinite(maxTorqueNm)) {
            throw new IllegalArgumentException("maxTorqueNm=" + maxTorqueNm + ": must be finite and > 0");
        }
        if (watchdogTimeoutNs < stepNs) {
            throw new IllegalArgumentException("watchdogTimeoutNs=" + watchdogTimeoutNs
                    + ": must be at least one step (stepNs=" + stepNs + ")");
        }
        if (maxSpinNs < 0 || maxSpinNs > MAX_SPIN_LIMIT_NS) {
            throw new IllegalArgumentException("maxSpinNs=" + maxSpinNs + ": must be within [0, "
                    + MAX_SPIN_LIMIT_NS + "]");
        }
    }

    /**
     * 0.5 ms steps, 4096 counts, 0.5 N·m, 100 ms watchdog, no spinning.
     *
     * @return the default settings
     */
    public static DspBoardConfig defaults() {
        return new DspBoardConfig(PendulumPlant.DEFAULT_STEP_NS, DEFAULT_COUNTS_PER_REVOLUTION,
                DEFAULT_MAX_TORQUE_NM, DEFAULT_WATCHDOG_TIMEOUT_NS, 0L);
    }

    /**
     * A copy with another step.
     *
     * @param step the board's cycle and plant step, within [10 µs, 10 ms] and no longer than the
     *     watchdog timeout
     * @return the copy
     * @throws IllegalArgumentException when {@code step} is out of range
     */
    public DspBoardConfig withStep(Duration step) {
        return new DspBoardConfig(Durations.toNs("step", step), countsPerRevolution, maxTorqueNm, watchdogTimeoutNs, maxSpinNs);
    }

    /**
     * A copy with another watchdog timeout.
     *
     * @param watchdogTimeout the timeout, at least one step
     * @return the copy
     * @throws IllegalArgumentException when {@code watchdogTimeout} is shorter than a step
     */
    public DspBoardConfig withWatchdogTimeout(Duration watchdogTimeout) {
        return new DspBoardConfig(stepNs, countsPerRevolution, maxTorqueNm, Durations.toNs("watchdogTimeout", watchdogTimeout),
                maxSpinNs);
    }

    /**
     * A copy with another torque range.
     *
     * @param torqueNm the largest torque magnitude the motor applies, in N·m, finite and positive
     * @return the copy
     * @throws IllegalArgumentException when {@code torqueNm} is out of range
     */
    public DspBoardConfig withMaxTorqueNm(double torqueNm) {
        return new DspBoardConfig(stepNs, countsPerRevolution, torqueNm, watchdogTimeoutNs, maxSpinNs);
    }

    /**
     * A copy with another spin bound.
     *
     * @param maxSpin the longest busy-wait before a step in real-time mode, within
     *     [0, {@value #MAX_SPIN_LIMIT_NS}] ns; zero to only sleep
     * @return the copy
     * @throws IllegalArgumentException when {@code maxSpin} is out of range
     */
    public DspBoardConfig withMaxSpin(Duration maxSpin) {
        return new DspBoardConfig(stepNs, countsPerRevolution, maxTorqueNm, watchdogTimeoutNs,
                Durations.toNs("maxSpin", maxSpin));
    }
}
