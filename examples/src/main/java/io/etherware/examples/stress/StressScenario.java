package io.etherware.examples.stress;

import io.etherware.core.message.Criticality;
import io.etherware.core.message.QoS;
import io.etherware.core.scheduler.Scheduler;
import io.etherware.core.time.NodeClock;
import io.etherware.examples.scenario.CpuLoad;
import io.etherware.examples.scenario.CycleLog;
import io.etherware.examples.scenario.GcActivity;
import io.etherware.examples.scenario.MissedCycles;
import io.etherware.examples.scenario.PendulumRig;
import io.etherware.examples.scenario.PlantProbe;
import io.etherware.examples.scenario.PlantWiring;
import io.etherware.examples.scenario.Progress;
import io.etherware.examples.scenario.RunSummary;
import io.etherware.examples.scenario.RunWatch;
import io.etherware.examples.scenario.ScenarioEvent;
import io.etherware.examples.scenario.ScenarioEvents;
import io.etherware.examples.scenario.ScenarioRun;
import io.etherware.examples.scenario.Schedulers;
import io.etherware.examples.scenario.SimThreads;
import io.etherware.pendulum.components.PendulumController;
import io.etherware.pendulum.control.GainSet;
import io.etherware.pendulum.plant.PendulumState;
import io.etherware.rt.platform.CpuPartition;
import io.etherware.rt.platform.CpuSet;
import io.etherware.rt.platform.Platform;
import io.etherware.rt.platform.ThreadGrant;
import io.etherware.rt.scheduling.DispatcherStats;
import io.etherware.rt.scheduling.RealtimeScheduler;
import io.etherware.services.notifier.Notifier;
import io.etherware.services.notifier.NotifierConfig;
import io.etherware.services.notifier.Subscription;
import io.etherware.services.notifier.SubscriptionStats;
import java.util.ArrayList;
import java.util.List;
import java.util.Locale;
import java.util.Objects;
import java.util.function.Function;
import org.slf4j.Logger;
import org.slf4j.LoggerFactory;

/**
 * The periodic-control-under-stress experiment of paper Section VI-B (Fig. 7 and 9), run once per
 * {@link Variant}: the controller, activated by HIGH Ticks every period, balances the pendulum
 * through the DSP proxy; the stressing task, activated by LOW Ticks every few seconds, computes
 * for about a second on the same node; ordinary threads load every core and allocate. Only the
 * node's scheduler differs between the variants; the simulated world (board, probe) and the
 * node's Notifier run at the same real-time priorities in both.
 *
 * <p>Not thread-safe: one thread runs the variants one after the other.
 */
public final class StressScenario {

    private static final Logger LOG = LoggerFactory.getLogger(StressScenario.class);
    /** Each variant's unrecorded warm-up. */
    private static final long WARM_UP_NS = 1_500_000_000L;
    /** The world's threads: the board and the probe. */
    private static final int SIM_THREADS = 2;
    private static final String CONTROL_TICKS = "controller";
    private static final String STRESS_TICKS = "stress";
    private static final long THREAD_START_TIMEOUT_NS = 2_000_000_000L;
    /** Cycles and samples kept beyond the expected count, for slack. */
    private static final int SLACK = 1_000;

    /** What runs the node in each run. */
    public enum Variant {
        /** The original Etherware: one dispatcher, first come first served, normal priority. */
        FIFO("fifo", "original Etherware", "FifoScheduler: one dispatcher, FIFO order, SCHED_OTHER"),
        /** Etherware-RT: Table II dispatchers at SCHED_FIFO priorities, Algorithm 1 placement. */
        RT("rt", "Etherware-RT", "RealtimeScheduler: Table II (0: OTHER, 1-3: FIFO 80/70/60), Algorithm 1");

        private final String key;
        private final String title;
        private final String description;

        Variant(String key, String title, String description) {
            this.key = key;
            this.title = title;
            this.description = description;
        }

        /** Short name for files and the command line: {@code fifo}, {@code rt}. */
        public String key() {
            return key;
        }

        /** The name in tables and legends. */
        public String title() {
            return title;
        }

        /** What scheduler it is, in one line. */
        public String description() {
            return description;
        }
    }

    private final StressConfig config;
    private final Function<String, Progress> progress;

    /**
     * A scenario with {@code config}; {@code progress} makes the progress line of each run from its
     * label.
     */
    public StressScenario(StressConfig config, Function<String, Progress> progress) {
        this.config = Objects.requireNonNull(config, "config");
        this.progress = Objects.requireNonNull(progress, "progress");
    }

    public StressConfig config() {
        return config;
    }

    /**
     * Runs each variant briefly (without load or stress) and discards the result, so that neither
     * measured run pays the JVM's class loading and JIT compilation of the loop's code.
     */
    public void warmUp() throws InterruptedException {
        StressConfig quiet = config.withDurationNs(WARM_UP_NS).withLoadThreads(0)
                .withFirstStressNs(WARM_UP_NS + config.stressEveryNs());
        for (Variant variant : Variant.values()) {
            execute(variant, quiet, null);
        }
    }

    /** Runs {@code variant} once, for the configured duration, and returns what it recorded. */
    public ScenarioRun run(Variant variant) throws InterruptedException {
        return execute(variant, config, progress.apply(variant.title()));
    }

    private ScenarioRun execute(Variant variant, StressConfig settings, Progress line) throws InterruptedException {
        CpuSet realtimeCpus = settings.realtimeCpus();
        // The same partition in both runs; the real-time scheduler shares it.
        try (CpuPartition partition = realtimeCpus.isInherit() ? null
                : Platform.current().partitionCpus(realtimeCpus)) {
            return executePartitioned(variant, settings, line);
        }
    }

    private ScenarioRun executePartitioned(Variant variant, StressConfig settings, Progress line)
            throws InterruptedException {
        long periodNs = settings.periodNs();
        int capacity = Math.toIntExact(settings.durationNs() / periodNs + SLACK);
        NodeClock clock = NodeClock.system();
        SimThreads threads = new SimThreads(settings.realtimeCpus());
        ScenarioEvents events = new ScenarioEvents();
        CycleLog cycles = new CycleLog(capacity, periodNs);
        RealtimeScheduler realtime = variant == Variant.RT ? Schedulers.etherwareRt(settings.realtimeCpus()) : null;
        Scheduler scheduler = realtime != null ? realtime : Schedulers.original();
        PendulumState initial = new PendulumState(0.0, 0.0, settings.initialTheta2Rad(), 0.0);
        GainSet gains = GainSet.v1Soft(PendulumRig.PARAMETERS);
        System.gc(); // each run starts from a collected heap, so the runs see comparable collector work

        GcActivity gcBefore = GcActivity.now();
        try (PendulumRig rig = new PendulumRig("stress-" + variant.key(), () -> scheduler, initial, gains, cycles,
                new PlantWiring(settings.baudRate()))) {
            rig.node().add(StressComponent.PROFILE, () -> new StressComponent(settings.stressWorkNs(), events));
            // The node's Notifier: SCHED_FIFO 82, above every dispatcher, in both runs.
            Notifier notifier = Notifier.install(rig.node(), NotifierConfig.defaults());
            PlantProbe probe = new PlantProbe(rig.board(), clock, periodNs, capacity, RunSummary.FALL_THRESHOLD_RAD,
                    events);
            CpuLoad load = CpuLoad.start(0); // no load threads until the world's threads run (below)
            long originNs;
            long firstReleaseNs;
            long endNs;
            SubscriptionStats controlTicks;
            SubscriptionStats stressTicks;
            try (probe) {
                originNs = rig.start(threads);
                firstReleaseNs = originNs + periodNs;
                notifier.subscribe(Subscription.periodic(CONTROL_TICKS, PendulumController.DEFAULT_PROFILE,
                        Criticality.HIGH, periodNs).startingAt(firstReleaseNs));
                notifier.subscribe(Subscription.periodic(STRESS_TICKS, StressComponent.PROFILE, Criticality.LOW,
                        settings.stressEveryNs()).startingAt(originNs + settings.firstStressNs()));
                probe.start(originNs, threads.fifo("plant-probe", SimThreads.PROBE_PRIORITY));
                // The load starts once the world's threads hold their priorities: a thread is born
                // at normal priority and would otherwise queue behind the load for its first step.
                threads.awaitConfigured(SIM_THREADS, THREAD_START_TIMEOUT_NS);
                load = CpuLoad.start(settings.loadThreads());
                endNs = originNs + settings.durationNs();
                var watch = new RunWatch(clock, originNs, firstReleaseNs, periodNs, probe, cycles, line);
                watch.until(endNs);
                watch.finish(endNs);
                controlTicks = notifier.unsubscribe(CONTROL_TICKS).orElseThrow();
                stressTicks = notifier.unsubscribe(STRESS_TICKS).orElseThrow();
            } finally {
                load.close();
            }
            GcActivity gc = GcActivity.now().since(gcBefore);
            List<ScenarioEvent> marks = events.snapshot();
            List<String> notes = new ArrayList<>();
            notes.add(String.format(Locale.ROOT, "%s: %s", variant.title(), variant.description()));
            MissedCycles.note(cycles.cycles(), periodNs, originNs, firstReleaseNs, endNs).ifPresent(notes::add);
            notes.add(String.format(Locale.ROOT, "  controller Ticks: sent %d, skipped %d late and %d busy, sending"
                    + " lateness p99 %.3f ms; stress Ticks sent %d, activations %d; cycles recorded %d (dropped %d)",
                    controlTicks.ticksSent(), controlTicks.skippedLate(), controlTicks.skippedBusy(),
                    controlTicks.latenessNs().percentileNs(99.0) / 1e6, stressTicks.ticksSent(),
                    marks.stream().filter(e -> e.kind() == ScenarioEvent.Kind.STRESS_START).count(),
                    cycles.cycles().size(), cycles.dropped()));
            notes.add(String.format(Locale.ROOT, "  load: %d threads allocated %.1f GiB; GC: %d collections, %d ms;"
                    + " DSP board late cycles %d", load.threadCount(), load.allocatedBytes() / (double) (1L << 30),
                    gc.collections(), gc.timeMs(), rig.board().lateCycles()));
            if (realtime != null) {
                notes.add(realtimeNote(realtime));
                realtime.platformReport().threads().forEach(grant -> notes.add("  " + grant.toLine()));
            }
            notifier.threadGrant().ifPresent(grant -> notes.add("  " + grant.toLine()));
            threads.grants().stream().map(ThreadGrant::toLine).forEach(grant -> notes.add("  " + grant));
            if (!threads.allGranted()) {
                LOG.warn("the simulated world did not get its real-time priorities; the runs compare less than"
                        + " the schedulers: {}", threads.grants());
            }
            return new ScenarioRun(variant.key(), variant.title(), periodNs, originNs, firstReleaseNs, endNs,
                    probe.samples(), cycles.cycles(), marks, notes);
        }
    }

    /** The scheduler-counted misses and each busy dispatcher's jobs and start latency, as a note line. */
    public static String realtimeNote(RealtimeScheduler scheduler) {
        var note = new StringBuilder(String.format(Locale.ROOT, "  scheduler-counted deadline misses %d;",
                scheduler.stats().deadlineMisses()));
        for (DispatcherStats dispatcher : scheduler.stats().dispatchers()) {
            if (dispatcher.jobsRun() > 0) {
                note.append(String.format(Locale.ROOT, " dispatcher %d: %d jobs, start latency p99 %.2f ms;",
                        dispatcher.dispatcherId(), dispatcher.jobsRun(),
                        dispatcher.startLatencyNs().percentileNs(99.0) / 1e6));
            }
        }
        return note.toString();
    }
}
