package io.etherware.examples.scenario;

import io.etherware.pendulum.components.ControlCycle;
import java.util.ArrayList;
import java.util.Comparator;
import java.util.HashSet;
import java.util.LinkedHashMap;
import java.util.List;
import java.util.Locale;
import java.util.Map;
import java.util.Optional;
import java.util.Set;

/**
 * Where a run's deadline misses fell, for its notes: a few misses tell more by when they came (the
 * first second, a stress burst, a collection) than by their count. The misses are those of
 * {@link RunSummary}: releases due before the run ended without a torque command within their
 * period. Stateless.
 */
public final class MissedCycles {

    /** Misses listed one by one; the rest are counted. */
    static final int LISTED = 12;

    private MissedCycles() {
    }

    /**
     * The note, e.g. {@code "  deadline misses at (s since the board started): 0.87 (torque 17.4 ms
     * after its release, started 0.9 ms late), 3.00 (no reading, given up 14.3 ms after its
     * release, started 0.5 ms late)"}, or empty when the run missed nothing.
     *
     * @param cycles         the run's control cycles, in any order
     * @param periodNs       the control period, which is also each release's deadline
     * @param originNs       time 0 of the note's seconds
     * @param firstReleaseNs the first release
     * @param endNs          the run's end: releases whose deadline is later are not counted
     * @return the note, indented as the other notes of a run
     */
    public static Optional<String> note(List<ControlCycle> cycles, long periodNs, long originNs, long firstReleaseNs,
            long endNs) {
        long releases = RunSummary.releasesDue(firstReleaseNs, endNs, periodNs);
        long lastDueReleaseNs = firstReleaseNs + (releases - 1) * periodNs;
        List<ControlCycle> due = cycles.stream().filter(c -> c.releaseNs() <= lastDueReleaseNs)
                .sorted(Comparator.comparingLong(ControlCycle::releaseNs)).toList();
        Set<Long> onTime = new HashSet<>();
        due.stream().filter(c -> CycleLog.isOnTime(c, periodNs)).forEach(c -> onTime.add(c.cycle()));
        long misses = Math.max(0, releases - onTime.size());
        if (misses == 0) {
            return Optional.empty();
        }
        Map<Long, ControlCycle> late = new LinkedHashMap<>();
        due.stream().filter(c -> !onTime.contains(c.cycle())).forEach(c -> late.putIfAbsent(c.cycle(), c));
        List<String> entries = new ArrayList<>();
        late.values().stream().limit(LISTED).forEach(c -> entries.add(entry(c, originNs)));
        var text = new StringBuilder("  deadline misses at (s since the board started): ");
        text.append(entries.isEmpty() ? "none with a control cycle" : String.join(", ", entries));
        if (late.size() > LISTED) {
            text.append(", and ").append(late.size() - LISTED).append(" more");
        }
        long withoutCycle = misses - late.size();
        if (withoutCycle > 0) {
            text.append("; ").append(withoutCycle).append(withoutCycle == 1 ? " release" : " releases")
                    .append(" without a control cycle");
            List<String> at = releasesWithoutCycle(due, periodNs, firstReleaseNs, releases).stream().limit(LISTED)
                    .map(releaseNs -> String.format(Locale.ROOT, "%.2f", (releaseNs - originNs) / 1e9)).toList();
            if (!at.isEmpty()) {
                text.append(", at ").append(String.join(", ", at)).append(withoutCycle > LISTED ? ", ..." : "");
            }
        }
        return Optional.of(text.toString());
    }

    /** The due releases no cycle was recorded for, by release time (cycles are matched to the nearest release). */
    private static List<Long> releasesWithoutCycle(List<ControlCycle> due, long periodNs, long firstReleaseNs,
            long releases) {
        Set<Long> recorded = new HashSet<>();
        for (ControlCycle cycle : due) {
            recorded.add(Math.floorDiv(cycle.releaseNs() - firstReleaseNs + periodNs / 2, periodNs));
        }
        List<Long> missing = new ArrayList<>();
        for (long k = 0; k < releases && missing.size() < LISTED; k++) {
            if (!recorded.contains(k)) {
                missing.add(firstReleaseNs + k * periodNs);
            }
        }
        return missing;
    }

    private static String entry(ControlCycle cycle, long originNs) {
        double atS = (cycle.releaseNs() - originNs) / 1e9;
        double responseMs = cycle.responseNs() / 1e6;
        double startedMs = cycle.startLatenessNs() / 1e6;
        return cycle.outcome() == ControlCycle.Outcome.COMMANDED
                ? String.format(Locale.ROOT, "%.2f (torque %.1f ms after its release, started %.1f ms late)", atS,
                        responseMs, startedMs)
                : String.format(Locale.ROOT, "%.2f (no reading, given up %.1f ms after its release, started %.1f ms"
                        + " late)", atS, responseMs, startedMs);
    }
}
