package io.etherware.examples.upgrade;

import io.etherware.examples.scenario.PlantWiring;
import java.nio.file.Path;
import java.util.Objects;

/**
 * Settings of the upgrade scenario (paper Section VI-C1). Immutable; validated at construction,
 * messages name the field, the value and the allowed range.
 *
 * @param durationNs       length of the run
 * @param periodNs         the controller's Tick period (the paper: 15 ms)
 * @param upgradeAtNs      when, after the board starts, the management request asks for V2
 * @param jar              the plugin jar holding controller V2 ({@link #V2_CLASS})
 * @param initialTheta2Rad where the pendulum starts, off upright
 * @param out              where the CSV, plots and table go
 * @param baudRate         the serial line rate to the DSP board
 * @param remote           the paper's topology (Fig. 10): the controller on node 2 in a second JVM,
 *                         upgraded by a request from the Requester on node 1; false: one node
 */
public record UpgradeConfig(long durationNs, long periodNs, long upgradeAtNs, Path jar, double initialTheta2Rad,
        Path out, int baudRate, boolean remote) {

    /** A minute: 30 s of V1, then 30 s of V2. */
    public static final long DEFAULT_DURATION_NS = 60_000_000_000L;
    /** The paper's 15 ms control period. */
    public static final long DEFAULT_PERIOD_NS = 15_000_000L;
    /** The least time on each controller version: V1 before the upgrade, V2 after it. */
    public static final long MIN_PHASE_NS = 1_000_000_000L;
    /** The shortest run: {@link #MIN_PHASE_NS} of V1, then as much of V2. */
    public static final long MIN_DURATION_NS = 2 * MIN_PHASE_NS;
    /** The paper's upgrade time: t = 30 s. */
    public static final long DEFAULT_UPGRADE_AT_NS = 30_000_000_000L;
    /** The class of controller V2 in the plugin jar. */
    public static final String V2_CLASS = "io.etherware.examples.upgrade.plugin.TightController";
    /** What the plugin jar's file name ends with. */
    public static final String JAR_SUFFIX = "-controller-v2.jar";

    public UpgradeConfig {
        Objects.requireNonNull(jar, "jar");
        Objects.requireNonNull(out, "out");
        if (durationNs < MIN_DURATION_NS || durationNs > 3_600_000_000_000L) {
            throw new IllegalArgumentException("durationNs=" + durationNs + ": must be within 2 s .. 1 h");
        }
        if (periodNs < 1_000_000L || periodNs > 1_000_000_000L) {
            throw new IllegalArgumentException("periodNs=" + periodNs + ": must be within 1 ms .. 1 s");
        }
        if (upgradeAtNs < MIN_PHASE_NS || upgradeAtNs > durationNs - MIN_PHASE_NS) {
            throw new IllegalArgumentException("upgradeAtNs=" + upgradeAtNs
                    + ": must leave at least 1 s of V1 before and 1 s of V2 after, within durationNs=" + durationNs);
        }
        PlantWiring.requireBaudRate(baudRate);
        if (!(Math.abs(initialTheta2Rad) < 0.3)) {
            throw new IllegalArgumentException("initialTheta2Rad=" + initialTheta2Rad + ": must be within ±0.3 rad");
        }
    }

    /** The defaults, or the upgrade half way through a run shorter than a minute. */
    public static UpgradeConfig of(long durationNs, long periodNs, Path jar, Path out) {
        return new UpgradeConfig(durationNs, periodNs, Math.min(DEFAULT_UPGRADE_AT_NS, durationNs / 2), jar, 0.02,
                out, PlantWiring.DEFAULT_BAUD_RATE, false);
    }

    /** A copy with the upgrade at another time. */
    public UpgradeConfig withUpgradeAtNs(long nanos) {
        return new UpgradeConfig(durationNs, periodNs, nanos, jar, initialTheta2Rad, out, baudRate, remote);
    }

    /** A copy with another serial line rate to the DSP board. */
    public UpgradeConfig withBaudRate(int bitsPerSecond) {
        return new UpgradeConfig(durationNs, periodNs, upgradeAtNs, jar, initialTheta2Rad, out, bitsPerSecond, remote);
    }

    /** A copy in the paper's two-node topology ({@code true}) or on one node. */
    public UpgradeConfig withRemote(boolean twoNodes) {
        return new UpgradeConfig(durationNs, periodNs, upgradeAtNs, jar, initialTheta2Rad, out, baudRate, twoNodes);
    }
}
