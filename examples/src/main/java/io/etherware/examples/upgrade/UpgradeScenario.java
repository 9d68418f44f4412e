package io.etherware.examples.upgrade;

import io.etherware.core.kernel.DeliveryWarmUp;
import io.etherware.core.message.Criticality;
import io.etherware.core.time.NodeClock;
import io.etherware.examples.migrate.ControlNodeCommand;
import io.etherware.examples.migrate.CycleReport;
import io.etherware.examples.migrate.MigrateConfig;
import io.etherware.examples.migrate.WarmUp;
import io.etherware.examples.scenario.ConfiguredController;
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
import io.etherware.pendulum.components.PendulumController;
import io.etherware.pendulum.control.GainSet;
import io.etherware.pendulum.plant.PendulumState;
import io.etherware.rt.scheduling.RealtimeScheduler;
import io.etherware.services.management.Implementation;
import io.etherware.services.management.Management;
import io.etherware.services.management.ManagementConfig;
import io.etherware.services.management.ManagementService;
import io.etherware.services.management.UpgradeResult;
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
import java.security.cert.CertificateEncodingException;
import java.time.Duration;
import java.util.ArrayList;
import java.util.List;
import java.util.Locale;
import java.util.Objects;
import java.util.concurrent.CompletableFuture;
import java.util.concurrent.CompletionException;
import java.util.concurrent.ExecutionException;
import java.util.concurrent.TimeUnit;
import java.util.concurrent.TimeoutException;
import java.util.function.LongSupplier;
import java.util.function.Supplier;
import org.slf4j.Logger;
import org.slf4j.LoggerFactory;

/**
 * The runtime upgrade of paper Section VI-C1 (Fig. 10 and 11): the pendulum balanced by
 * controller V1 (soft gains) on Etherware-RT; at the configured time a HIGH management request
 * asks the node to replace it with controller V2 (tight gains), a class the management service
 * loads at runtime from a plugin jar in an allowlisted directory, signed for the run by a key the
 * node trusts. V2 takes over V1's state at a message boundary and the loop goes on.
 *
 * <p>On one node by default; with {@link UpgradeConfig#remote()}, in the paper's topology: the
 * controller on node 2 in a second JVM, the request from the {@link Requester} component on the
 * plant's node 1. Unlike the paper, which stops the old instance before it starts the new one,
 * the management service loads and constructs V2 while V1 still runs and swaps them at one
 * message boundary (DESIGN decision 8): the loop then waits only for the state's hand-over, not
 * for class loading.
 *
 * <p>Not thread-safe: one thread runs it.
 */
public final class UpgradeScenario {

    private static final Logger LOG = LoggerFactory.getLogger(UpgradeScenario.class);
    private static final String CONTROL_TICKS = "controller";
    private static final long ANSWER_TIMEOUT_NS = TimeUnit.SECONDS.toNanos(15);
    private static final int SLACK = 1_000;
    private static final long NODE_START_TIMEOUT_S = 60;

    private final UpgradeConfig config;
    private final Progress line;

    /** A scenario with {@code config}, reporting progress on {@code line} (null: silent). */
    public UpgradeScenario(UpgradeConfig config, Progress line) {
        this.config = Objects.requireNonNull(config, "config");
        this.line = line;
    }

    /**
     * Runs the scenario: signs a copy of the plugin jar with a key made for the run (a node loads
     * only plugins signed by a key it trusts), and has the node that hosts the controller trust
     * that key alone.
     *
     * @throws IllegalStateException if the plugin jar is missing (before anything starts)
     * @throws IOException           if the jar cannot be signed (keytool and jarsigner need a JDK), or
     *                               node 2's JVM cannot be started or does not come up
     */
    public UpgradeOutcome run() throws InterruptedException, IOException {
        if (!Files.isRegularFile(config.jar())) {
            throw new IllegalStateException("the plugin jar " + config.jar().toAbsolutePath()
                    + " does not exist: build it with ./mvnw -pl examples -am -DskipTests package");
        }
        PluginSigner.Signed plugin = PluginSigner.signForThisRun(config.jar().toAbsolutePath(),
                config.out().toAbsolutePath());
        if (line != null) {
            line.note(plugin.line());
        }
        long periodNs = config.periodNs();
        int capacity = Math.toIntExact(config.durationNs() / periodNs + SLACK);
        var run = new Run(new SimThreads(), new ScenarioEvents(), new CycleLog(capacity, periodNs), capacity,
                Schedulers.etherwareRt());
        String listenerName = "upgrade-scenario-" + System.identityHashCode(run.cycles);
        PendulumState initial = new PendulumState(0.0, 0.0, config.initialTheta2Rad(), 0.0);
        Implementation v2 = Implementation.fromJar(plugin.jar(), UpgradeConfig.V2_CLASS)
                .withConfiguration(ConfiguredController.configuration(listenerName));
        return config.remote() ? runOnTwoNodes(plugin, run, listenerName, initial, v2)
                : runOnOneNode(plugin, run, listenerName, initial, v2);
    }

    /** What both topologies share: the threads, the records, the node 1 scheduler. */
    private record Run(SimThreads threads, ScenarioEvents events, CycleLog cycles, int capacity,
                       RealtimeScheduler scheduler) {
    }

    private UpgradeOutcome runOnOneNode(PluginSigner.Signed plugin, Run run, String listenerName,
                                        PendulumState initial, Implementation v2) throws InterruptedException {
        GainSet v1 = GainSet.v1Soft(PendulumRig.PARAMETERS);
        try (ControlListeners.Registration registration = ControlListeners.register(listenerName, run.cycles);
                PendulumRig rig = new PendulumRig("upgrade", run::scheduler, initial, v1, run.cycles,
                        new PlantWiring(config.baudRate()))) {
            Notifier notifier = Notifier.install(rig.node(), NotifierConfig.defaults());
            ManagementService.install(rig.node(), ManagementConfig.builder().settleWait(MigrateConfig.SETTLE_WAIT)
                    .allowDirectory(plugin.jar().getParent()).trustedSigner(plugin.certificate()).build());
            String setup = "Etherware-RT: RealtimeScheduler: Table II (0: OTHER, 1-3: FIFO 80/70/60), Algorithm 1;"
                    + " controller V1 " + v1.name() + " " + v1.polesRadPerS();
            return balanceAndUpgrade(rig, notifier, run, () -> rig.start(run.threads), setup,
                    () -> Management.upgrade(rig.node(), rig.node().nodeId(), PendulumController.DEFAULT_PROFILE, v2,
                            Duration.ofNanos(ANSWER_TIMEOUT_NS)));
        }
    }

    /**
     * The paper's topology (Fig. 10): node 1 (this JVM) holds the board, the DSPProxy, the
     * Notifier and the {@link Requester}; node 2 ({@link ControlNodeCommand}, a second JVM) runs
     * controller V1 and trusts the run's signing key for the plugin directory; the Requester asks
     * node 2 for the upgrade at HIGH criticality.
     */
    private UpgradeOutcome runOnTwoNodes(PluginSigner.Signed plugin, Run run, String listenerName,
                                         PendulumState initial, Implementation v2)
            throws InterruptedException, IOException {
        Path certificate = config.out().toAbsolutePath().resolve("plugin-signer.cer");
        try {
            Files.write(certificate, plugin.certificate().getEncoded());
        } catch (CertificateEncodingException e) {
            throw new IOException("the run's signing certificate cannot be written: " + e.getMessage(), e);
        }
        try (PendulumRig rig = new PendulumRig(MigrateConfig.PLANT_NODE, run::scheduler, initial,
                new PlantWiring(config.baudRate()))) {
            // Node 2's controllers, V1 and then V2, report their cycles here by message.
            rig.node().add(CycleReport.RECORDER, CycleReport.recorder(rig.node(), run.cycles::onCycle));
            rig.node().add(Requester.PROFILE, Requester::new);
            // The Requester's request and its answer cross the network; no management service here
            // registers their contents.
            Management.registerContents(rig.node().contentsTypes());
            rig.node().start();
            DeliveryWarmUp.run(rig.node());
            try (NetworkMessenger net = NetworkMessenger.start(rig.node(), NetworkConfig.builder()
                    .codec(WarmUp.warmedCodec(rig.node())).listen(new InetSocketAddress("127.0.0.1", 0))
                    .build())) {
                Notifier notifier = Notifier.install(rig.node(), NotifierConfig.defaults());
                Path nodeLog = config.out().resolve("node-2.log");
                NodeProcess node2 = NodeProcess.start(List.of("control-node", "--connect",
                        NodeProcess.hostPort(net.localAddress()), "--listener", listenerName,
                        "--plugins", plugin.jar().getParent().toString(), "--trust", certificate.toString()),
                        nodeLog, NODE_START_TIMEOUT_S);
                try {
                    if (!net.awaitResolvable(PendulumController.DEFAULT_PROFILE, Duration.ofSeconds(30))) {
                        throw new IOException("node 2's controller does not resolve on node 1; see " + nodeLog);
                    }
                    String setup = "Etherware-RT on both nodes: RealtimeScheduler, Table II (0: OTHER, 1-3: FIFO"
                            + " 80/70/60), Algorithm 1; controller V1 on node 2 in a second JVM (pid " + node2.pid()
                            + "), asked for V2 by the Requester on node 1 over TCP on loopback";
                    return balanceAndUpgrade(rig, notifier, run, () -> rig.startBoard(run.threads), setup,
                            () -> Requester.ask(rig.node(), context -> Management.upgrade(context,
                                    MigrateConfig.CONTROL_NODE, PendulumController.DEFAULT_PROFILE, v2,
                                    Duration.ofNanos(ANSWER_TIMEOUT_NS))));
                } finally {
                    node2.stop();
                }
            }
        }
    }

    private UpgradeOutcome balanceAndUpgrade(PendulumRig rig, Notifier notifier, Run run, LongSupplier start,
                                             String setup, Supplier<CompletableFuture<UpgradeResult>> upgrade)
            throws InterruptedException {
        long periodNs = config.periodNs();
        NodeClock clock = NodeClock.system();
        CycleLog cycles = run.cycles;
        ScenarioEvents events = run.events;
        PlantProbe probe = new PlantProbe(rig.board(), clock, periodNs, run.capacity, RunSummary.FALL_THRESHOLD_RAD,
                events);
        long originNs;
        long firstReleaseNs;
        long endNs;
        UpgradeResult result = null;
        String failure = null;
        long requestNs;
        long answerNs;
        SubscriptionStats ticks;
        try (probe) {
            originNs = start.getAsLong();
            firstReleaseNs = originNs + periodNs;
            notifier.subscribe(Subscription.periodic(CONTROL_TICKS, PendulumController.DEFAULT_PROFILE,
                    Criticality.HIGH, periodNs).startingAt(firstReleaseNs));
            probe.start(originNs, run.threads.fifo("plant-probe", SimThreads.PROBE_PRIORITY));
            endNs = originNs + config.durationNs();
            var watch = new RunWatch(clock, originNs, firstReleaseNs, periodNs, probe, cycles, line);
            watch.until(originNs + config.upgradeAtNs());

            requestNs = clock.nanoTime();
            events.add(requestNs, ScenarioEvent.Kind.UPGRADE, "upgrade request");
            try {
                result = upgrade.get().get(ANSWER_TIMEOUT_NS, TimeUnit.NANOSECONDS);
            } catch (ExecutionException | CompletionException | TimeoutException e) {
                failure = (e.getCause() != null ? e.getCause() : e).toString();
                LOG.error("the upgrade failed; V1 serves on: {}", failure);
            }
            answerNs = clock.nanoTime();
            if (failure != null) {
                events.add(answerNs, ScenarioEvent.Kind.NOTE, "upgrade failed");
            }
            watch.until(endNs);
            watch.finish(endNs);
            ticks = notifier.unsubscribe(CONTROL_TICKS).orElseThrow();
        }
        List<String> notes = new ArrayList<>();
        notes.add(setup);
        notes.add(String.format(Locale.ROOT, "  controller Ticks: sent %d, skipped %d late and %d busy;"
                + " cycles recorded %d (dropped %d); scheduler-counted deadline misses %d; DSP board late"
                + " cycles %d", ticks.ticksSent(), ticks.skippedLate(), ticks.skippedBusy(),
                cycles.cycles().size(), cycles.dropped(), run.scheduler.stats().deadlineMisses(),
                rig.board().lateCycles()));
        notifier.threadGrant().ifPresent(grant -> notes.add("  " + grant.toLine()));
        run.threads.grants().forEach(grant -> notes.add("  " + grant.toLine()));
        List<ControlCycle> recorded = cycles.cycles();
        // V2's first cycle, for the CSV and for where the "after" figures start.
        long v2FromNs = recorded.stream().filter(c -> c.gainVersion() == 2).mapToLong(ControlCycle::releaseNs)
                .min().orElse(answerNs);
        if (result != null) {
            events.add(v2FromNs, ScenarioEvent.Kind.NOTE, "V2 first cycle");
        }
        ScenarioRun scenarioRun = new ScenarioRun("upgrade", "V1 → V2 upgrade", periodNs, originNs, firstReleaseNs,
                endNs, probe.samples(), recorded, events.snapshot(), notes);
        return new UpgradeOutcome(scenarioRun, result, failure, requestNs, Math.min(answerNs, v2FromNs), answerNs,
                ticks.skippedReleases());
    }
}
