package io.etherware.examples.scenario;

import io.etherware.pendulum.components.ControlCycle;
import java.util.Arrays;
import java.util.Comparator;
import java.util.List;

/**
 * The figures of one run that a control engineer compares (paper Section VI-B): how far the
 * pendulum leaned, how regular the control period was, how many periods went without a timely
 * command, and whether the pendulum fell. Immutable.
 *
 * <p>Definitions. θ2 comes from the plant's ground truth ({@link ProbeSamples}). The
 * <b>control-period jitter</b> is |Δ − period| for the interval Δ between successive torque
 * commands, gaps included: a controller starved for a second shows a one-second jitter. A
 * <b>deadline miss</b> is a Tick release whose deadline (release + period) passed before the run
 * ended without a torque command computed for it within that period, whether its Tick came late,
 * its reading failed or it never ran.
 *
 * @param maxAbsTheta2Rad largest |θ2|
 * @param rmsTheta1Rad    root mean square of θ1, the arm's wander around its set point 0
 * @param rmsTheta2Rad    root mean square of θ2
 * @param jitterP50Ms     median control-period jitter, ms (NaN with fewer than two commands)
 * @param jitterP99Ms     99th percentile of the jitter, ms
 * @param jitterMaxMs     largest jitter, ms
 * @param deadlineMisses  releases without a command within their period
 * @param releases        releases whose deadline passed during the run
 * @param fell            whether |θ2| passed {@link #FALL_THRESHOLD_RAD}
 * @param fellAtS         when it first did, seconds since the origin (NaN if it did not)
 */
public record RunSummary(double maxAbsTheta2Rad, double rmsTheta1Rad, double rmsTheta2Rad, double jitterP50Ms, double jitterP99Ms,
        double jitterMaxMs, long deadlineMisses, long releases, boolean fell, double fellAtS) {

    /** The pendulum counts as fallen beyond this |θ2|: far outside what a balancing loop recovers. */
    public static final double FALL_THRESHOLD_RAD = 0.5;

    /** The summary of {@code run}. */
    public static RunSummary of(ScenarioRun run) {
        ProbeSamples samples = run.samples();
        long periodNs = run.periodNs();
        long[] jitterNs = jitterNs(run.cycles(), periodNs);
        Arrays.sort(jitterNs);
        long releases = releasesDue(run.firstReleaseNs(), run.endNs(), periodNs);
        long lastDueReleaseNs = run.firstReleaseNs() + (releases - 1) * periodNs;
        long onTime = run.cycles().stream()
                .filter(c -> c.releaseNs() <= lastDueReleaseNs && CycleLog.isOnTime(c, periodNs))
                .mapToLong(ControlCycle::cycle).distinct().count();
        long fellAtNs = samples.firstTimeAboveNs(FALL_THRESHOLD_RAD);
        return new RunSummary(samples.maxAbsTheta2Rad(), samples.rmsTheta1Rad(), samples.rmsTheta2Rad(), percentileMs(jitterNs, 0.50),
                percentileMs(jitterNs, 0.99), jitterNs.length == 0 ? Double.NaN : jitterNs[jitterNs.length - 1] / 1e6,
                Math.max(0, releases - onTime), releases, fellAtNs >= 0,
                fellAtNs >= 0 ? run.secondsOf(fellAtNs) : Double.NaN);
    }

    /** Releases {@code first + k * period} whose deadline {@code release + period} is at or before {@code endNs}. */
    public static long releasesDue(long firstReleaseNs, long endNs, long periodNs) {
        long span = endNs - firstReleaseNs - periodNs;
        return span < 0 ? 0 : span / periodNs + 1;
    }

    /** |Δ − period| between successive torque commands (by readout time), gaps included. */
    static long[] jitterNs(List<ControlCycle> cycles, long periodNs) {
        long[] commandsNs = cycles.stream().filter(c -> c.outcome() == ControlCycle.Outcome.COMMANDED)
                .sorted(Comparator.comparingLong(ControlCycle::readoutNs)).mapToLong(ControlCycle::readoutNs)
                .toArray();
        long[] jitter = new long[Math.max(0, commandsNs.length - 1)];
        for (int i = 1; i < commandsNs.length; i++) {
            jitter[i - 1] = Math.abs(commandsNs[i] - commandsNs[i - 1] - periodNs);
        }
        return jitter;
    }

    private static double percentileMs(long[] sortedNs, double quantile) {
        if (sortedNs.length == 0) {
            return Double.NaN;
        }
        int index = (int) Math.ceil(quantile * sortedNs.length) - 1;
        return sortedNs[Math.clamp(index, 0, sortedNs.length - 1)] / 1e6;
    }
}
