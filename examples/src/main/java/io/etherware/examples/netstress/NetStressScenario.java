package io.etherware.examples.netstress;

import io.etherware.core.codec.MessageCodec;
import io.etherware.core.kernel.DeliveryWarmUp;
import io.etherware.core.message.Criticality;
import io.etherware.core.message.Message;
import io.etherware.core.message.Profile;
import io.etherware.core.message.QoS;
import io.etherware.core.scheduler.Scheduler;
import io.etherware.core.time.NodeClock;
import io.etherware.examples.migrate.CycleReport;
import io.etherware.examples.migrate.WarmUp;
import io.etherware.examples.scenario.CpuLoad;
import io.etherware.examples.scenario.CycleLog;
import io.etherware.examples.scenario.GcActivity;
import io.etherware.examples.scenario.MissedCycles;
import io.etherware.examples.scenario.NodeProcess;
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
import io.etherware.examples.stress.StressComponent;
import io.etherware.examples.stress.StressConfig;
import io.etherware.examples.stress.StressScenario;
import io.etherware.examples.stress.StressScenario.Variant;
import io.etherware.pendulum.components.DspProxy;
import io.etherware.pendulum.components.DspProxyStatus;
import io.etherware.pendulum.components.PendulumController;
import io.etherware.pendulum.components.StatusRequest;
import io.etherware.pendulum.plant.PendulumState;
import io.etherware.rt.platform.ThreadGrant;
import io.etherware.rt.platform.CpuPartition;
import io.etherware.rt.platform.CpuSet;
import io.etherware.rt.platform.Platform;
import io.etherware.rt.platform.ThreadPolicy;
import io.etherware.rt.scheduling.RealtimeScheduler;
import io.etherware.services.network.NetworkConfig;
import io.etherware.services.network.NetworkMessenger;
import io.etherware.services.notifier.Notifier;
import io.etherware.services.notifier.NotifierConfig;
import io.etherware.services.notifier.Subscription;
import io.etherware.services.notifier.SubscriptionStats;
import java.io.IOException;
import java.net.InetSocketAddress;
import java.nio.file.Files;
import java.nio.file.Path;
import java.time.Duration;
import java.util.ArrayList;
import java.util.List;
import java.util.Locale;
import java.util.Objects;
import java.util.function.Function;
import org.slf4j.Logger;
import org.slf4j.LoggerFactory;

/**
 * The stress experiment of paper Section VI-B in the two-node topology of Fig. 10, once per
 * {@link Variant}: node 1 (this JVM) holds the DSP board behind its serial link, the DSPProxy and
 * the Notifier; node 2 (a second JVM per run, {@link NetStressNodeCommand}) runs the controller, so
 * each control cycle crosses the network twice (the Tick and the reading to node 2, the command
 * back). Both nodes run a stress task on LOW Ticks (about a second every few seconds) and ordinary
 * load threads; node 2's stress comes an offset after node 1's, by default half a stress period,
 * so that the two never compute at once (see {@link #DEFAULT_NODE2_OFFSET_FRACTION}). Only the software differs between the variants: the
 * schedulers of both nodes and the network threads (ordinary on the original Etherware, SCHED_FIFO
 * above the HIGH dispatcher on Etherware-RT, the messenger's default). The simulated world and the
 * Notifiers run at the same real-time priorities in both.
 *
 * <p>Not thread-safe: one thread runs the variants one after the other.
 */
public final class NetStressScenario {

    /** The node with the DSP board and the DSPProxy (the paper's node 1). */
    public static final String PLANT_NODE = "node-1";
    /** The node with the controller (the paper's node 2), in a JVM of its own. */
    public static final String CONTROL_NODE = "node-2";
    /** Node 2's stress task; node 1's is {@link StressComponent#PROFILE}. */
    public static final Profile NODE2_STRESS = Profile.of("stress", "pendulum", "2");

    /**
     * Node 2's stress task runs this fraction of the stress period after node 1's by default. Both
     * nodes share one host here (2 cores on the development machine), unlike the paper's machines:
     * two stress tasks at SCHED_FIFO at once hold every core, the kernel's real-time throttling
     * ({@code sched_rt_runtime_us} 950000 of 1000000) then stops every real-time thread of a core,
     * the board's too, for up to most of a second (seen: a 0.9 s freeze of node 1's board and probe,
     * "sched: RT throttling activated" in the kernel log, and Etherware-RT's pendulum falling in 1
     * of 6 short runs). Staggered, the host carries what the single-node stress puts on it.
     */
    public static final double DEFAULT_NODE2_OFFSET_FRACTION = 0.5;

    private static final Logger LOG = LoggerFactory.getLogger(NetStressScenario.class);
    /** Each variant's unrecorded warm-up, node 2's JVM included. */
    private static final long WARM_UP_NS = 1_500_000_000L;
    private static final int SIM_THREADS = 2;
    private static final String CONTROL_TICKS = "controller";
    private static final String STRESS_TICKS = "stress";
    private static final long THREAD_START_TIMEOUT_NS = 2_000_000_000L;
    private static final long NODE_START_TIMEOUT_S = 60;
    private static final Duration RESOLVE_TIMEOUT = Duration.ofSeconds(30);
    /** How long the DSPProxy has to answer the status request at the end of a run. */
    private static final Duration STATUS_TIMEOUT = Duration.ofSeconds(2);
    private static final int SLACK = 1_000;

    private final StressConfig config;
    private final long node2OffsetNs;
    private final Function<String, Progress> progress;
    /** Where both nodes' real-time threads run; inherit: every CPU, no partition. */
    private final CpuSet realtimeCpus;

    /**
     * A scenario with {@code config}, node 2's stress {@code node2OffsetNs} after node 1's (0: at
     * the same times); {@code progress} makes the progress line of each run from its label. With
     * {@code config.realtimeCpus()} named, the CPUs are partitioned: every real-time thread of both
     * nodes (dispatchers, network threads, Notifiers, the board and the probe) there, every other
     * thread of both JVMs on the remaining CPUs, so that no ordinary Java thread waits, runnable,
     * behind a real-time one (a safepoint waits for every such thread, stopping the real-time ones
     * too).
     */
    public NetStressScenario(StressConfig config, long node2OffsetNs, Function<String, Progress> progress) {
        this.realtimeCpus = config.realtimeCpus();
        this.config = Objects.requireNonNull(config, "config");
        if (node2OffsetNs < 0 || node2OffsetNs >= config.stressEveryNs()) {
            throw new IllegalArgumentException("node2OffsetNs=" + node2OffsetNs + ": must be within 0 .. stressEveryNs="
                    + config.stressEveryNs() + " (exclusive)");
        }
        this.node2OffsetNs = node2OffsetNs;
        this.progress = Objects.requireNonNull(progress, "progress");
    }

    /** The default offset of node 2's stress for {@code config}: {@link #DEFAULT_NODE2_OFFSET_FRACTION} of its period. */
    public static long defaultNode2OffsetNs(StressConfig config) {
        return Math.round(config.stressEveryNs() * DEFAULT_NODE2_OFFSET_FRACTION);
    }

    /** How long after node 1's stress node 2's comes. */
    public long node2OffsetNs() {
        return node2OffsetNs;
    }

    public StressConfig config() {
        return config;
    }

    /**
     * A node's messenger settings in {@code variant}, on loopback: ordinary network threads on the
     * original Etherware, the messenger's default (SCHED_FIFO above the highest dispatcher) on
     * Etherware-RT.
     */
    static NetworkConfig.Builder network(Variant variant, MessageCodec codec, CpuSet realtimeCpus) {
        NetworkConfig.Builder builder = NetworkConfig.builder().codec(codec)
                .listen(new InetSocketAddress("127.0.0.1", 0));
        return variant == Variant.FIFO ? builder.threads(ThreadPolicy.NON_REALTIME) : builder.threadCpus(realtimeCpus);
    }

    /** What the network threads are in {@code variant}, in a few words. */
    static String networkDescription(Variant variant) {
        return variant == Variant.FIFO ? "network threads SCHED_OTHER"
                : "network threads SCHED_FIFO above the HIGH dispatcher";
    }

    /**
     * Runs each variant briefly (without load or stress, node 2's JVM included) and discards the
     * result, so that node 1's JVM does not pay its class loading and JIT compilation in the first
     * measured run only.
     */
    public void warmUp() throws IOException, InterruptedException {
        StressConfig quiet = config.withDurationNs(WARM_UP_NS).withLoadThreads(0)
                .withFirstStressNs(WARM_UP_NS + config.stressEveryNs());
        for (Variant variant : Variant.values()) {
            execute(variant, quiet, null, "-warmup");
        }
    }

    /**
     * Runs {@code variant} once, for the configured duration, and returns what it recorded.
     *
     * @throws IOException if node 2's JVM cannot be started or its controller does not resolve
     */
    public NetStressRun run(Variant variant) throws IOException, InterruptedException {
        return execute(variant, config, progress.apply(variant.title()), "");
    }

    private NetStressRun execute(Variant variant, StressConfig settings, Progress line, String logSuffix)
            throws IOException, InterruptedException {
        long periodNs = settings.periodNs();
        int capacity = Math.toIntExact(settings.durationNs() / periodNs + SLACK);
        Files.createDirectories(settings.out());
        // Every ordinary thread of this JVM, and node 2's JVM (it inherits this thread's affinity),
        // off the real-time CPUs, in both runs; the real-time scheduler shares the partition.
        try (CpuPartition partition = realtimeCpus.isInherit() ? null
                : Platform.current().partitionCpus(realtimeCpus)) {
            return execute(variant, settings, line, logSuffix, periodNs, capacity);
        }
    }

    private NetStressRun execute(Variant variant, StressConfig settings, Progress line, String logSuffix, long periodNs,
            int capacity) throws IOException, InterruptedException {
        NodeClock clock = NodeClock.system();
        SimThreads threads = new SimThreads(realtimeCpus);
        ScenarioEvents events = new ScenarioEvents();
        CycleLog cycles = new CycleLog(capacity, periodNs);
        RealtimeScheduler realtime = variant == Variant.RT ? Schedulers.etherwareRt(realtimeCpus) : null;
        Scheduler scheduler = realtime != null ? realtime : Schedulers.original();
        PendulumState initial = new PendulumState(0.0, 0.0, settings.initialTheta2Rad(), 0.0);
        String listenerName = "netstress-" + variant.key() + "-" + System.identityHashCode(cycles);
        System.gc(); // each run starts from a collected heap, so the runs see comparable collector work

        GcActivity gcBefore = GcActivity.now();
        try (PendulumRig rig = new PendulumRig(PLANT_NODE, () -> scheduler, initial,
                new PlantWiring(settings.baudRate()))) {
            rig.node().add(CycleReport.RECORDER, CycleReport.recorder(rig.node(), cycles));
            rig.node().add(StressComponent.PROFILE, () -> new StressComponent(settings.stressWorkNs(), events));
            rig.node().start();
            DeliveryWarmUp.run(rig.node()); // as the other two-JVM scenarios: see its documentation
            try (NetworkMessenger net = NetworkMessenger.start(rig.node(),
                    network(variant, WarmUp.warmedCodec(rig.node()), realtimeCpus).build())) {
                // Node 1's Notifier: SCHED_FIFO 82, above every dispatcher, in both runs.
                Notifier notifier = Notifier.install(rig.node(), NotifierConfig.defaults().withCpus(realtimeCpus));
                Path log = settings.out().resolve("node-2-" + variant.key() + logSuffix + ".log");
                NodeProcess node2 = NodeProcess.start(List.of("netstress-node",
                        "--connect", NodeProcess.hostPort(net.localAddress()), "--listener", listenerName,
                        "--variant", variant.name(), "--stress-every-ms", Long.toString(settings.stressEveryNs()
                                / 1_000_000L), "--stress-ms", Long.toString(settings.stressWorkNs() / 1_000_000L),
                        "--load-threads", Integer.toString(settings.loadThreads()), "--rt-cpus",
                        realtimeCpus.toString()), log, NODE_START_TIMEOUT_S);
                Balanced balanced;
                List<String> printed;
                try {
                    if (!net.awaitResolvable(PendulumController.DEFAULT_PROFILE, RESOLVE_TIMEOUT)) {
                        throw new IOException("node 2's controller does not resolve on node 1; see " + log);
                    }
                    balanced = balance(rig, notifier, node2, settings, node2OffsetNs, clock, threads, events, cycles,
                            capacity, line);
                } finally {
                    printed = node2.stop();
                }
                Results node2Results = Results.parse(printed);
                GcActivity gc = GcActivity.now().since(gcBefore);
                return record(variant, settings, rig, notifier, realtime, threads, events, cycles, balanced,
                        node2Results, node2.pid(), gc, net);
            }
        }
    }

    /** What a balanced run leaves behind on node 1 apart from the logs. */
    private record Balanced(long originNs, long firstReleaseNs, long endNs, PlantProbe probe,
            SubscriptionStats controlTicks, SubscriptionStats stressTicks, int loadThreads, long loadBytes) {
    }

    private static Balanced balance(PendulumRig rig, Notifier notifier, NodeProcess node2, StressConfig settings,
            long node2OffsetNs, NodeClock clock, SimThreads threads, ScenarioEvents events, CycleLog cycles, int capacity, Progress line)
            throws IOException {
        long periodNs = settings.periodNs();
        PlantProbe probe = new PlantProbe(rig.board(), clock, periodNs, capacity, RunSummary.FALL_THRESHOLD_RAD,
                events);
        CpuLoad load = CpuLoad.start(0); // no load threads until the world's threads run (below)
        try (probe) {
            long originNs = rig.startBoard(threads);
            long firstReleaseNs = originNs + periodNs;
            long firstStressNs = originNs + settings.firstStressNs();
            notifier.subscribe(Subscription.periodic(CONTROL_TICKS, PendulumController.DEFAULT_PROFILE,
                    Criticality.HIGH, periodNs).startingAt(firstReleaseNs));
            notifier.subscribe(Subscription.periodic(STRESS_TICKS, StressComponent.PROFILE, Criticality.LOW,
                    settings.stressEveryNs()).startingAt(firstStressNs));
            probe.start(originNs, threads.fifo("plant-probe", SimThreads.PROBE_PRIORITY));
            // The load starts once the world's threads hold their priorities (see StressScenario);
            // node 2 starts its load now too, and its stress Ticks the offset after node 1's.
            threads.awaitConfigured(SIM_THREADS, THREAD_START_TIMEOUT_NS);
            node2.send(NetStressNodeCommand.START + " " + (firstStressNs + node2OffsetNs));
            load = CpuLoad.start(settings.loadThreads());
            long endNs = originNs + settings.durationNs();
            var watch = new RunWatch(clock, originNs, firstReleaseNs, periodNs, probe, cycles, line);
            watch.until(endNs);
            watch.finish(endNs);
            SubscriptionStats controlTicks = notifier.unsubscribe(CONTROL_TICKS).orElseThrow();
            SubscriptionStats stressTicks = notifier.unsubscribe(STRESS_TICKS).orElseThrow();
            return new Balanced(originNs, firstReleaseNs, endNs, probe, controlTicks, stressTicks, load.threadCount(),
                    load.allocatedBytes());
        } finally {
            load.close();
        }
    }

    /**
     * Node 1's DSPProxy and its serial client, counted since the rig started: a reading the
     * controller gave up on may have waited for a resent serial request (the client's timeout).
     */
    private static String dspProxyNote(PendulumRig rig) {
        try {
            Message reply = rig.node().requestBlocking(DspProxy.DEFAULT_PROFILE, new StatusRequest(false),
                    QoS.of(Criticality.MIDDLE), STATUS_TIMEOUT.toNanos());
            DspProxyStatus status = reply.contentsAs(DspProxyStatus.class);
            return String.format(Locale.ROOT, "  node 1: DSPProxy readings %d, commands %d, exchanges failed for"
                    + " want of a reply %d; its serial client: requests %d, attempts that timed out %d, stale"
                    + " replies %d, frames rejected %d", status.proxy().angleReads(), status.proxy().torqueCommands(),
                    status.proxy().timeouts(), status.link().requests(), status.link().timeouts(),
                    status.link().staleReplies(), status.link().framesRejected());
        } catch (RuntimeException e) {
            return "  node 1: DSPProxy counters not read: " + e.getMessage();
        }
    }

    private static NetStressRun record(Variant variant, StressConfig settings, PendulumRig rig, Notifier notifier,
            RealtimeScheduler realtime, SimThreads threads, ScenarioEvents events, CycleLog cycles, Balanced run,
            Results node2, long node2Pid, GcActivity gc, NetworkMessenger net) {
        long node1Activations = events.snapshot().stream()
                .filter(e -> e.kind() == ScenarioEvent.Kind.STRESS_START).count();
        // Node 2's stress marks join node 1's (one host, one monotonic clock): the plots shade both.
        for (ScenarioEvent mark : node2.events()) {
            events.add(mark.timeNs(), mark.kind(), "node-2 " + mark.label());
        }
        List<ScenarioEvent> marks = events.snapshot();
        List<String> notes = new ArrayList<>();
        notes.add(String.format(Locale.ROOT, "%s: on both nodes %s; %s; node 2 in a second JVM (pid %d), TCP on"
                + " loopback", variant.title(), variant.description(), networkDescription(variant), node2Pid));
        MissedCycles.note(cycles.cycles(), settings.periodNs(), run.originNs(), run.firstReleaseNs(), run.endNs())
                .ifPresent(notes::add);
        notes.add(dspProxyNote(rig));
        notes.add(String.format(Locale.ROOT, "  node 1: controller Ticks sent %d, skipped %d late, %d busy and %d"
                + " undeliverable, sending lateness p99 %.3f ms; stress Ticks sent %d, activations %d; cycles"
                + " recorded %d (dropped %d)", run.controlTicks().ticksSent(), run.controlTicks().skippedLate(),
                run.controlTicks().skippedBusy(), run.controlTicks().skippedUndeliverable(),
                run.controlTicks().latenessNs().percentileNs(99.0) / 1e6, run.stressTicks().ticksSent(),
                node1Activations, cycles.cycles().size(), cycles.dropped()));
        notes.add(String.format(Locale.ROOT, "  node 1: load: %d threads allocated %.1f GiB; GC: %d collections, %d"
                + " ms; DSP board late cycles %d; network threads %s", run.loadThreads(),
                run.loadBytes() / (double) (1L << 30), gc.collections(), gc.timeMs(), rig.board().lateCycles(),
                net.ioThreadPolicy()));
        if (realtime != null) {
            notes.add(StressScenario.realtimeNote(realtime).replaceFirst("^  ", "  node 1: "));
            realtime.platformReport().threads().forEach(grant -> notes.add("  node 1: " + grant.toLine()));
        }
        notifier.threadGrant().ifPresent(grant -> notes.add("  node 1: " + grant.toLine()));
        threads.grants().stream().map(ThreadGrant::toLine).forEach(grant -> notes.add("  node 1: " + grant));
        notes.addAll(node2.notes());
        if (!threads.allGranted()) {
            LOG.warn("the simulated world did not get its real-time priorities; the runs compare less than"
                    + " the schedulers: {}", threads.grants());
        }
        ScenarioRun scenarioRun = new ScenarioRun(variant.key(), variant.title(), settings.periodNs(), run.originNs(),
                run.firstReleaseNs(), run.endNs(), run.probe().samples(), cycles.cycles(), marks, notes);
        return new NetStressRun(scenarioRun, realtime != null ? realtime.stats().deadlineMisses() : Results.NOT_COUNTED,
                node2.misses(), node1Activations, node2.activations());
    }
}
