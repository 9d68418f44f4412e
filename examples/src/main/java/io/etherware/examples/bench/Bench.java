package io.etherware.examples.bench;

import java.io.PrintWriter;
import java.time.Instant;
import java.util.ArrayList;
import java.util.List;
import java.util.Locale;
import java.util.Set;

/**
 * The whole bench in one JVM: sections 1 to 7 in order, each row Etherware-RT beside its
 * baselines, then the report. Sections run one after another so they do not disturb each other;
 * the garbage collector's pauses are watched throughout.
 *
 * <p>Call {@link #run} from an ordinary (non-real-time) thread; it starts and stops every thread
 * it needs and leaves none running.
 */
public final class Bench {

    /** Section 7's name. */
    static final String GC_SECTION = "7. collector pauses";

    private final BenchConfig config;
    private final Set<Integer> sections;
    private final String settings;
    private final PrintWriter progress;

    /**
     * @param config   what to measure and for how long
     * @param sections the sections to run, 1 to 6 (section 7, the collector, is always reported);
     *                 empty for all
     * @param settings the settings as the user gave them, for the report's header
     * @param progress where to say which section is running (standard error)
     */
    public Bench(BenchConfig config, Set<Integer> sections, String settings, PrintWriter progress) {
        this.config = config;
        this.sections = Set.copyOf(sections);
        this.settings = settings;
        this.progress = progress;
    }

    /** Runs every section and returns the report (not yet written). */
    public BenchReport run() throws Exception {
        Instant startedAt = Instant.now();
        long startNs = System.nanoTime();
        MachineInfo machine = MachineInfo.probe(config.priority());
        var rows = new ArrayList<BenchRow>();
        try (CollectorPauses pauses = CollectorPauses.start()) {
            section(1, PeriodicLateness.SECTION, rows, () -> new PeriodicLateness(config).measure());
            section(2, DispatchLatency.SECTION, rows, () -> new DispatchLatency(config).measure());
            section(3, Throughput.SECTION, rows, () -> new Throughput(config).measure());
            section(4, CodecCost.SECTION, rows, () -> new CodecCost(config).measure());
            section(5, Loopback.SECTION, rows, () -> new Loopback(config).measure());
            section(6, GapMeasurement.SECTION, rows, () -> ReconfigurationGaps.defaults().measure(config));
            CollectorPauses.Summary summary = pauses.summary();
            rows.add(BenchRow.value("gc.pauses", GC_SECTION, String.join(", ", machine.collectors()),
                    "whole run", summary.maxPauseMs(), "ms max", String.format(Locale.ROOT,
                            "%d pauses; JVM options: %s", summary.pauseCount(), String.join(" ", machine.jvmOptions()))));
            return new BenchReport(startedAt.toString(), settings, machine, rows, summary, (System.nanoTime() - startNs) / 1e9);
        }
    }

    @FunctionalInterface
    private interface Section {
        List<BenchRow> measure() throws Exception;
    }

    private void section(int number, String name, List<BenchRow> rows, Section section) throws Exception {
        if (!sections.isEmpty() && !sections.contains(number)) {
            return;
        }
        long startNs = System.nanoTime();
        progress.printf(Locale.ROOT, "bench: %s ...%n", name);
        progress.flush();
        List<BenchRow> measured = section.measure();
        rows.addAll(measured);
        progress.printf(Locale.ROOT, "bench: %s done in %.1f s (%d rows)%n", name, (System.nanoTime() - startNs) / 1e9,
                measured.size());
        progress.flush();
    }
}
