package io.etherware.examples.scenario;

import io.etherware.core.time.NodeClock;
import java.util.Objects;
import java.util.concurrent.locks.LockSupport;

/**
 * Waits out a run on the calling thread (the scenario's main thread, at normal priority),
 * updating the progress line twice a second with θ2 and the deadline misses so far.
 *
 * <p>Not thread-safe: one thread calls it.
 */
public final class RunWatch {

    private static final long UPDATE_EVERY_NS = 500_000_000L;

    private final NodeClock clock;
    private final long originNs;
    private final long firstReleaseNs;
    private final long periodNs;
    private final PlantProbe probe;
    private final CycleLog cycles;
    private final Progress line;

    /**
     * Watches a run that started at {@code originNs}, with releases from {@code firstReleaseNs}
     * every {@code periodNs}; {@code line} may be null (a warm-up prints nothing).
     */
    public RunWatch(NodeClock clock, long originNs, long firstReleaseNs, long periodNs, PlantProbe probe,
            CycleLog cycles, Progress line) {
        this.clock = Objects.requireNonNull(clock, "clock");
        this.originNs = originNs;
        this.firstReleaseNs = firstReleaseNs;
        this.periodNs = periodNs;
        this.probe = Objects.requireNonNull(probe, "probe");
        this.cycles = Objects.requireNonNull(cycles, "cycles");
        this.line = line;
    }

    /** Sleeps until {@code untilNs} on the clock, updating the progress line. */
    public void until(long untilNs) {
        long nowNs;
        while ((nowNs = clock.nanoTime()) - untilNs < 0) {
            LockSupport.parkNanos(Math.min(UPDATE_EVERY_NS, untilNs - nowNs));
            nowNs = clock.nanoTime();
            if (line != null) {
                line.update((nowNs - originNs) / 1e9, probe.lastTheta2Rad(), missesBy(nowNs));
            }
        }
    }

    /** Ends the progress line with the state at {@code endNs}. */
    public void finish(long endNs) {
        if (line != null) {
            line.finish((endNs - originNs) / 1e9, probe.lastTheta2Rad(), missesBy(endNs));
        }
    }

    /** Releases due by {@code nowNs} without a timely torque command. */
    public long missesBy(long nowNs) {
        return Math.max(0, RunSummary.releasesDue(firstReleaseNs, nowNs, periodNs) - cycles.onTimeCycles());
    }
}
