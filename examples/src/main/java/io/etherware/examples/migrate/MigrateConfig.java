package io.etherware.examples.migrate;

import io.etherware.examples.scenario.PlantWiring;
import io.etherware.services.management.AccessRule;
import io.etherware.services.management.ManagementConfig;
import java.nio.file.Path;
import java.time.Duration;
import java.util.Objects;
import java.util.Set;

/**
 * Settings of the migration scenario (paper Section VI-C2). Immutable; validated at construction,
 * messages name the field, the value and the allowed range.
 *
 * @param durationNs       length of the run
 * @param periodNs         the controller's Tick period (the paper: 15 ms)
 * @param migrateAtNs      when, after the board starts, the requester asks node 2 to move the
 *                         controller to node 1
 * @param initialTheta2Rad where the pendulum starts, off upright
 * @param out              where the CSV, plots and table go
 */
public record MigrateConfig(long durationNs, long periodNs, long migrateAtNs, double initialTheta2Rad, Path out,
        int baudRate) {

    /** A minute: 40 s on node 2, then 20 s on node 1. */
    public static final long DEFAULT_DURATION_NS = 60_000_000_000L;
    /** The least time on each node: node 2 before the migration, node 1 after it. */
    public static final long MIN_PHASE_NS = 2_000_000_000L;
    /** The shortest run: {@link #MIN_PHASE_NS} on node 2, then as much on node 1. */
    public static final long MIN_DURATION_NS = 2 * MIN_PHASE_NS;
    /** The paper's migration time: t = 40 s. */
    public static final long DEFAULT_MIGRATE_AT_NS = 40_000_000_000L;
    /** The node with the DSP board and the DSPProxy (the paper's node 1): the migration's target. */
    public static final String PLANT_NODE = "node-1";
    /** The node the controller starts on (the paper's node 2), in a JVM of its own. */
    public static final String CONTROL_NODE = "node-2";

    public MigrateConfig {
        Objects.requireNonNull(out, "out");
        if (durationNs < MIN_DURATION_NS || durationNs > 3_600_000_000_000L) {
            throw new IllegalArgumentException("durationNs=" + durationNs + ": must be within 4 s .. 1 h");
        }
        if (periodNs < 1_000_000L || periodNs > 1_000_000_000L) {
            throw new IllegalArgumentException("periodNs=" + periodNs + ": must be within 1 ms .. 1 s");
        }
        if (migrateAtNs < MIN_PHASE_NS || migrateAtNs > durationNs - MIN_PHASE_NS) {
            throw new IllegalArgumentException("migrateAtNs=" + migrateAtNs
                    + ": must leave at least 2 s on each node, within durationNs=" + durationNs);
        }
        PlantWiring.requireBaudRate(baudRate);
        if (!(Math.abs(initialTheta2Rad) < 0.3)) {
            throw new IllegalArgumentException("initialTheta2Rad=" + initialTheta2Rad + ": must be within ±0.3 rad");
        }
    }

    /**
     * The defaults, or the migration two thirds into a run shorter than a minute, and no later
     * than {@link #MIN_PHASE_NS} before the end of a run shorter than 6 s.
     */
    public static MigrateConfig of(long durationNs, long periodNs, Path out) {
        long migrateAtNs = Math.min(DEFAULT_MIGRATE_AT_NS, Math.min(durationNs * 2 / 3, durationNs - MIN_PHASE_NS));
        return new MigrateConfig(durationNs, periodNs, migrateAtNs, 0.02, out, PlantWiring.DEFAULT_BAUD_RATE);
    }

    /**
     * The management service of either node: {@code peer} may migrate controllers (the pendulum's
     * and the warm-up's spare) to and from it. The scenario's two JVMs talk plain TCP on loopback,
     * which does not authenticate the peer, so that is allowed explicitly.
     */
    public static ManagementConfig management(String peer) {
        return managementBuilder(peer).build();
    }

    /**
     * How long the scenarios' management services wait for the controller to have no reading in
     * flight before they hold it (migration) or swap its logic (upgrade): a few control periods
     * more than the default, so that even a loaded machine's late reply reaches the logic that
     * asked, and no cycle is lost.
     */
    public static final Duration SETTLE_WAIT = Duration.ofMillis(500);

    /** {@link #management}'s builder, for a node that allows more. */
    public static ManagementConfig.Builder managementBuilder(String peer) {
        return ManagementConfig.builder().allowRemote(peer, Set.of(AccessRule.Operation.MIGRATE), "controller")
                .allowUnauthenticatedLinks(true).settleWait(SETTLE_WAIT);
    }

    /** A copy with the migration at another time. */
    public MigrateConfig withMigrateAtNs(long nanos) {
        return new MigrateConfig(durationNs, periodNs, nanos, initialTheta2Rad, out, baudRate);
    }

    /** A copy with another serial line rate to the DSP board. */
    public MigrateConfig withBaudRate(int bitsPerSecond) {
        return new MigrateConfig(durationNs, periodNs, migrateAtNs, initialTheta2Rad, out, bitsPerSecond);
    }
}
