package io.etherware.examples.migrate;

import io.etherware.core.kernel.DeliveryWarmUp;
import io.etherware.core.kernel.Endpoint;
import io.etherware.core.message.Criticality;
import io.etherware.core.time.NodeClock;
import io.etherware.examples.scenario.ControlListeners;
import io.etherware.examples.scenario.CycleLog;
import io.etherware.examples.scenario.NodeProcess;
import io.etherware.examples.scenario.PendulumRig;
import io.etherware.examples.scenario.PlantProbe;
import io.etherware.examples.scenario.PlantWiring;
import io.etherware.examples.scenario.Progress;
import io.etherware.examples.scenario.Requester;
import io.etherware.examples.scenario.RunSummary;
import io.etherware.examples.scenario.RunWatch;
import io.etherware.examples.scenario.ScenarioEvent;
import io.etherware.examples.scenario.ScenarioEvents;
import io.etherware.examples.scenario.ScenarioRun;
import io.etherware.examples.scenario.Schedulers;
import io.etherware.examples.scenario.SimThreads;
import io.etherware.pendulum.components.ControlCycle;
import io.etherware.pendulum.components.ControlListener;
import io.etherware.pendulum.components.PendulumController;
import io.etherware.pendulum.plant.PendulumState;
import io.etherware.rt.scheduling.RealtimeScheduler;
import io.etherware.services.management.Implementation;
import io.etherware.services.management.Management;
import io.etherware.services.management.ManagementService;
import io.etherware.services.management.MigrateRequest;
import io.etherware.services.management.MigrationResult;
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
import java.util.concurrent.CompletionException;
import java.util.concurrent.ExecutionException;
import java.util.concurrent.TimeUnit;
import java.util.concurrent.TimeoutException;
import java.util.concurrent.atomic.AtomicReference;
import org.slf4j.Logger;
import org.slf4j.LoggerFactory;

/**
 * The runtime controller migration of paper Section VI-C2 (Fig. 10 and 12), across two JVMs on
 * loopback. Node 1 (this JVM) holds the DSP board behind its serial link, the DSPProxy and the
 * Notifier; node 2 (a second JVM, {@link ControlNodeCommand}) runs the controller, which reads the
 * angles and commands the torque through the DSPProxy over TCP. At the configured time the
 * {@link Requester} component on node 1 sends node 2 a HIGH management request to move the
 * controller to node 1 (as in Fig. 10); node 2
 * quiesces it at a message boundary and ships its state as XML, node 1 restores it and takes over
 * the profile, and the loop goes on.
 *
 * <p>The Ticks come from node 1's Notifier, where the board's clock is: the subscription names the
 * controller's profile, which routes to node 2 before the migration and to node 1 after it, so it
 * follows the controller without being touched. Each instance reports its cycles to the plant's
 * node: node 2's by message ({@link CycleReport}), node 1's directly; both JVMs share the host's
 * monotonic clock, so their times line up.
 *
 * <p>Not thread-safe: one thread runs it.
 */
public final class MigrateScenario {

    private static final Logger LOG = LoggerFactory.getLogger(MigrateScenario.class);
    private static final String CONTROL_TICKS = "controller";
    private static final long ANSWER_TIMEOUT_NS = TimeUnit.SECONDS.toNanos(15);
    private static final long NODE_START_TIMEOUT_S = 60;
    private static final int SLACK = 1_000;

    private final MigrateConfig config;
    private final Progress line;

    /** A scenario with {@code config}, reporting progress on {@code line} (null: silent). */
    public MigrateScenario(MigrateConfig config, Progress line) {
        this.config = Objects.requireNonNull(config, "config");
        this.line = line;
    }

    /**
     * Runs the scenario: starts node 2's JVM, balances, migrates, stops node 2.
     *
     * @throws IOException if node 2's JVM cannot be started or does not come up
     */
    public MigrateOutcome run() throws IOException, InterruptedException {
        long periodNs = config.periodNs();
        int capacity = Math.toIntExact(config.durationNs() / periodNs + SLACK);
        Files.createDirectories(config.out());
        NodeClock clock = NodeClock.system();
        SimThreads threads = new SimThreads();
        ScenarioEvents events = new ScenarioEvents();
        CycleLog cycles = new CycleLog(capacity, periodNs);
        var lastRemote = new AtomicReference<ControlCycle>();
        var firstLocal = new AtomicReference<ControlCycle>();
        ControlListener remote = cycle -> {
            if (cycle.outcome() == ControlCycle.Outcome.COMMANDED) {
                lastRemote.set(cycle);
            }
            cycles.onCycle(cycle);
        };
        ControlListener local = cycle -> {
            if (cycle.outcome() == ControlCycle.Outcome.COMMANDED) {
                firstLocal.compareAndSet(null, cycle);
            }
            cycles.onCycle(cycle);
        };
        String listenerName = "migrate-scenario-" + System.identityHashCode(cycles);
        RealtimeScheduler scheduler = Schedulers.etherwareRt();
        PendulumState initial = new PendulumState(0.0, 0.0, config.initialTheta2Rad(), 0.0);

        try (ControlListeners.Registration registration = ControlListeners.register(listenerName, local);
                PendulumRig rig = new PendulumRig(MigrateConfig.PLANT_NODE, () -> scheduler, initial,
                        new PlantWiring(config.baudRate()))) {
            rig.node().add(CycleReport.RECORDER, CycleReport.recorder(rig.node(), remote));
            rig.node().add(Requester.PROFILE, Requester::new);
            rig.node().start();
            DeliveryWarmUp.run(rig.node());
            try (NetworkMessenger net = NetworkMessenger.start(rig.node(), NetworkConfig.builder()
                    .codec(WarmUp.warmedCodec(rig.node())).listen(new InetSocketAddress("127.0.0.1", 0))
                    .build())) {
                // Node 2 moves the controller here: its migration steps are requests from node 2.
                ManagementService.install(rig.node(), MigrateConfig.management(MigrateConfig.CONTROL_NODE), net);
                Notifier notifier = Notifier.install(rig.node(), NotifierConfig.defaults());
                Path nodeLog = config.out().resolve("node-2.log");
                NodeProcess node2 = NodeProcess.start(List.of("control-node", "--connect",
                        NodeProcess.hostPort(net.localAddress()), "--listener", listenerName), nodeLog,
                        NODE_START_TIMEOUT_S);
                try {
                    if (!net.awaitResolvable(PendulumController.DEFAULT_PROFILE, Duration.ofSeconds(30))) {
                        throw new IOException("node 2's controller does not resolve on node 1; see " + nodeLog);
                    }
                    rehearse(rig, listenerName);
                    return balanceAndMigrate(rig, notifier, node2, clock, threads, events, cycles, capacity,
                            scheduler, lastRemote, firstLocal, listenerName);
                } finally {
                    node2.stop();
                }
            }
        }
    }

    private MigrateOutcome balanceAndMigrate(PendulumRig rig, Notifier notifier, NodeProcess node2, NodeClock clock,
            SimThreads threads, ScenarioEvents events, CycleLog cycles, int capacity, RealtimeScheduler scheduler,
            AtomicReference<ControlCycle> lastRemote, AtomicReference<ControlCycle> firstLocal, String listenerName)
            throws InterruptedException {
        long periodNs = config.periodNs();
        PlantProbe probe = new PlantProbe(rig.board(), clock, periodNs, capacity, RunSummary.FALL_THRESHOLD_RAD,
                events);
        long originNs;
        long firstReleaseNs;
        long endNs;
        long requestNs;
        long answerNs;
        MigrationResult result = null;
        String failure = null;
        SubscriptionStats ticks;
        try (probe) {
            originNs = rig.startBoard(threads);
            firstReleaseNs = originNs + periodNs;
            notifier.subscribe(Subscription.periodic(CONTROL_TICKS, PendulumController.DEFAULT_PROFILE,
                    Criticality.HIGH, periodNs).startingAt(firstReleaseNs));
            probe.start(originNs, threads.fifo("plant-probe", SimThreads.PROBE_PRIORITY));
            endNs = originNs + config.durationNs();
            var watch = new RunWatch(clock, originNs, firstReleaseNs, periodNs, probe, cycles, line);
            watch.until(originNs + config.migrateAtNs());

            requestNs = clock.nanoTime();
            events.add(requestNs, ScenarioEvent.Kind.MIGRATION, "migration request");
            var request = MigrateRequest.of(PendulumController.DEFAULT_PROFILE, MigrateConfig.PLANT_NODE,
                    Implementation.ofClass(ListenedController.class)
                            .withConfiguration(ListenedController.configuration(listenerName)));
            try {
                result = Requester.ask(rig.node(), context -> Management.migrate(context, MigrateConfig.CONTROL_NODE,
                        request, Duration.ofNanos(ANSWER_TIMEOUT_NS))).get(ANSWER_TIMEOUT_NS, TimeUnit.NANOSECONDS);
            } catch (ExecutionException | CompletionException | TimeoutException e) {
                failure = (e.getCause() != null ? e.getCause() : e).toString();
                LOG.error("the migration failed; the controller runs on at node 2: {}", failure);
                events.add(clock.nanoTime(), ScenarioEvent.Kind.NOTE, "migration failed");
            }
            answerNs = clock.nanoTime();
            watch.until(endNs);
            watch.finish(endNs);
            ticks = notifier.unsubscribe(CONTROL_TICKS).orElseThrow();
        }
        MigrateOutcome.HandOver handOver = null;
        ControlCycle before = lastRemote.get();
        ControlCycle after = firstLocal.get();
        if (after != null && before != null) {
            handOver = new MigrateOutcome.HandOver(before.cycle(), after.cycle(), before.readoutNs(), after.readoutNs());
            events.add(after.releaseNs(), ScenarioEvent.Kind.NOTE, "first cycle on node 1");
        }
        String finalHost = rig.node().registry().resolve(PendulumController.DEFAULT_PROFILE) instanceof Endpoint.Local
                ? MigrateConfig.PLANT_NODE : "not " + MigrateConfig.PLANT_NODE;

        List<String> notes = new ArrayList<>();
        notes.add("Etherware-RT on both nodes: RealtimeScheduler, Table II (0: OTHER, 1-3: FIFO 80/70/60), Algorithm 1;"
                + " node 2 in a second JVM (pid " + node2.pid() + "), TCP on loopback");
        notes.add(String.format(Locale.ROOT, "  controller Ticks from node 1's Notifier: sent %d, skipped %d late,"
                + " %d busy and %d undeliverable; cycles recorded %d (dropped %d); node 1's scheduler-counted deadline"
                + " misses %d; DSP board late cycles %d, at most %.1f ms behind the physical clock", ticks.ticksSent(),
                ticks.skippedLate(), ticks.skippedBusy(), ticks.skippedUndeliverable(), cycles.cycles().size(),
                cycles.dropped(), scheduler.stats().deadlineMisses(), rig.board().lateCycles(),
                rig.board().maxLagNs() / 1e6));
        notifier.threadGrant().ifPresent(grant -> notes.add("  " + grant.toLine()));
        threads.grants().forEach(grant -> notes.add("  " + grant.toLine()));
        ScenarioRun run = new ScenarioRun("migrate", "node 2 → node 1 migration", periodNs, originNs, firstReleaseNs,
                endNs, probe.samples(), cycles.cycles(), events.snapshot(), notes);
        return new MigrateOutcome(run, result, failure, requestNs, answerNs, handOver, finalHost,
                ticks.skippedReleases());
    }

    /**
     * Migrates node 2's idle spare controller to node 1 once, then removes it, before the pendulum
     * starts: the first migration of a JVM pays for class loading and Jackson's first use of the
     * management contents (hundreds of milliseconds here), which the real one should not.
     */
    private static void rehearse(PendulumRig rig, String listenerName) throws InterruptedException {
        var request = MigrateRequest.of(WarmUp.REHEARSAL, MigrateConfig.PLANT_NODE,
                Implementation.ofClass(ListenedController.class)
                        .withConfiguration(ListenedController.configuration(listenerName)));
        try {
            MigrationResult result = Requester.ask(rig.node(), context -> Management.migrate(context,
                    MigrateConfig.CONTROL_NODE, request, Duration.ofNanos(ANSWER_TIMEOUT_NS)))
                    .get(ANSWER_TIMEOUT_NS, TimeUnit.NANOSECONDS);
            LOG.info("rehearsal: the spare controller moved to node 1 in {} ms; removing it", result.totalNs() / 1e6);
            rig.node().remove(WarmUp.REHEARSAL);
        } catch (ExecutionException | TimeoutException e) {
            LOG.warn("rehearsal migration failed ({}); the real one will run cold", e.toString());
        }
    }
}
