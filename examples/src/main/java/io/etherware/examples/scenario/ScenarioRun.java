package io.etherware.examples.scenario;

import io.etherware.pendulum.components.ControlCycle;
import java.util.Arrays;
import java.util.List;
import java.util.Objects;

/**
 * Everything one scenario run recorded, for the CSV, the plots and the summary. Times are on the
 * node's monotonic clock; the run's time 0 is {@code originNs}, when the DSP board started.
 * Immutable apart from the sample arrays, which belong to the run.
 *
 * @param key            short name for file names, e.g. {@code fifo}
 * @param title          what ran, for tables and plot legends, e.g. {@code original Etherware}
 * @param periodNs       the control period
 * @param originNs       when the board started
 * @param firstReleaseNs the controller's first Tick release
 * @param endNs          when the Ticks stopped
 * @param samples        the plant's ground truth, one sample per control period
 * @param cycles         the controller's cycles as it saw them
 * @param events         what happened, in time order
 * @param notes          further lines for the report: ticks, GC, thread priorities, scheduler counts
 */
public record ScenarioRun(String key, String title, long periodNs, long originNs, long firstReleaseNs, long endNs,
        ProbeSamples samples, List<ControlCycle> cycles, List<ScenarioEvent> events, List<String> notes) {

    public ScenarioRun {
        Objects.requireNonNull(key, "key");
        Objects.requireNonNull(title, "title");
        Objects.requireNonNull(samples, "samples");
        if (periodNs <= 0) {
            throw new IllegalArgumentException("periodNs=" + periodNs + ": must be > 0");
        }
        if (endNs < firstReleaseNs) {
            throw new IllegalArgumentException("endNs=" + endNs + " is before firstReleaseNs=" + firstReleaseNs);
        }
        cycles = List.copyOf(cycles);
        events = List.copyOf(events);
        notes = List.copyOf(notes);
    }

    /** Seconds since the run's origin. */
    public double secondsOf(long timeNs) {
        return (timeNs - originNs) / 1e9;
    }

    /** The run's length in seconds, origin to end. */
    public double durationS() {
        return secondsOf(endNs);
    }

    /**
     * The part of this run from {@code fromNs} to {@code toNs} (e.g. before and after an upgrade):
     * the samples and events in that span, the cycles released in it, and the first release of the
     * span on this run's release grid. The origin stays this run's, so times read the same.
     */
    public ScenarioRun slice(String sliceKey, String sliceTitle, long fromNs, long toNs) {
        if (toNs < fromNs) {
            throw new IllegalArgumentException("toNs=" + toNs + " is before fromNs=" + fromNs);
        }
        long first = firstReleaseNs;
        if (fromNs > first) {
            first += ((fromNs - first + periodNs - 1) / periodNs) * periodNs;
        }
        long firstRelease = first;
        long end = Math.min(Math.max(toNs, firstRelease), endNs);
        int from = 0;
        while (from < samples.size() && samples.timeNs()[from] < fromNs) {
            from++;
        }
        int to = from;
        while (to < samples.size() && samples.timeNs()[to] < toNs) {
            to++;
        }
        ProbeSamples part = new ProbeSamples(Arrays.copyOfRange(samples.timeNs(), from, to),
                Arrays.copyOfRange(samples.theta1Rad(), from, to),
                Arrays.copyOfRange(samples.theta2Rad(), from, to),
                Arrays.copyOfRange(samples.torqueNm(), from, to));
        return new ScenarioRun(sliceKey, sliceTitle, periodNs, originNs, firstRelease, Math.max(end, firstRelease),
                part, cycles.stream().filter(c -> c.releaseNs() >= firstRelease && c.releaseNs() < toNs).toList(),
                events.stream().filter(e -> e.timeNs() >= fromNs && e.timeNs() < toNs).toList(), notes);
    }
}
