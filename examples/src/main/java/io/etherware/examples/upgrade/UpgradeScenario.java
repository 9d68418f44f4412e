package io.etherware.examples.upgrade;

import io.etherware.core.message.Criticality;
import io.etherware.core.time.NodeClock;
import io.etherware.examples.scenario.ConfiguredController;
import io.etherware.examples.scenario.ControlListeners;
import io.etherware.examples.scenario.CycleLog;
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
import io.etherware.services.notifier.Notifier;
import io.etherware.services.notifier.NotifierConfig;
import io.etherware.services.notifier.Subscription;
import io.etherware.services.notifier.SubscriptionStats;
import java.io.IOException;
import java.nio.file.Files;
import java.time.Duration;
import java.util.ArrayList;
import java.util.List;
import java.util.Locale;
import java.util.Objects;
import java.util.concurrent.CompletionException;
import java.util.concurrent.ExecutionException;
import java.util.concurrent.TimeUnit;
import java.util.concurrent.TimeoutException;
import org.slf4j.Logger;
import org.slf4j.LoggerFactory;

/**
 * The runtime upgrade of paper Section VI-C1 (Fig. 10 and 11): the pendulum balanced by
 * controller V1 (soft gains) on Etherware-RT; at the configured time a HIGH management request
 * asks the node to replace it with controller V2 (tight gains), a class the management service
 * loads at runtime from a plugin jar in an allowlisted directory, signed for the run by a key the
 * node trusts. V2 takes over V1's state at a message boundary and the loop goes on.
 *
 * <p>Not thread-safe: one thread runs it.
 */
public final class UpgradeScenario {

    private static final Logger LOG = LoggerFactory.getLogger(UpgradeScenario.class);
    private static final String CONTROL_TICKS = "controller";
    private static final long ANSWER_TIMEOUT_NS = TimeUnit.SECONDS.toNanos(15);
    private static final int SLACK = 1_000;

    private final UpgradeConfig config;
    private final Progress line;

    /** A scenario with {@code config}, reporting progress on {@code line} (null: silent). */
    public UpgradeScenario(UpgradeConfig config, Progress line) {
        this.config = Objects.requireNonNull(config, "config");
        this.line = line;
    }

    /**
     * Runs the scenario: signs a copy of the plugin jar with a key made for the run (a node loads
     * only plugins signed by a key it trusts), and has the node trust that key alone.
     *
     * @throws IllegalStateException if the plugin jar is missing (before anything starts)
     * @throws IOException           if the jar cannot be signed (keytool and jarsigner need a JDK)
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
        NodeClock clock = NodeClock.system();
        SimThreads threads = new SimThreads();
        ScenarioEvents events = new ScenarioEvents();
        CycleLog cycles = new CycleLog(capacity, periodNs);
        String listenerName = "upgrade-scenario-" + System.identityHashCode(cycles);
        RealtimeScheduler scheduler = Schedulers.etherwareRt();
        PendulumState initial = new PendulumState(0.0, 0.0, config.initialTheta2Rad(), 0.0);
        GainSet v1 = GainSet.v1Soft(PendulumRig.PARAMETERS);

        try (ControlListeners.Registration registration = ControlListeners.register(listenerName, cycles);
                PendulumRig rig = new PendulumRig("upgrade", () -> scheduler, initial, v1, cycles,
                        new PlantWiring(config.baudRate()))) {
            Notifier notifier = Notifier.install(rig.node(), NotifierConfig.defaults());
            ManagementService.install(rig.node(), ManagementConfig.builder()
                    .allowDirectory(plugin.jar().getParent()).trustedSigner(plugin.certificate()).build());
            PlantProbe probe = new PlantProbe(rig.board(), clock, periodNs, capacity, RunSummary.FALL_THRESHOLD_RAD,
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
                originNs = rig.start(threads);
                firstReleaseNs = originNs + periodNs;
                notifier.subscribe(Subscription.periodic(CONTROL_TICKS, PendulumController.DEFAULT_PROFILE,
                        Criticality.HIGH, periodNs).startingAt(firstReleaseNs));
                probe.start(originNs, threads.fifo("plant-probe", SimThreads.PROBE_PRIORITY));
                endNs = originNs + config.durationNs();
                var watch = new RunWatch(clock, originNs, firstReleaseNs, periodNs, probe, cycles, line);
                watch.until(originNs + config.upgradeAtNs());

                requestNs = clock.nanoTime();
                events.add(requestNs, ScenarioEvent.Kind.UPGRADE, "upgrade request");
                Implementation v2 = Implementation.fromJar(plugin.jar(), UpgradeConfig.V2_CLASS)
                        .withConfiguration(ConfiguredController.configuration(listenerName));
                try {
                    result = Management.upgrade(rig.node(), rig.node().nodeId(), PendulumController.DEFAULT_PROFILE,
                            v2, Duration.ofNanos(ANSWER_TIMEOUT_NS)).get(ANSWER_TIMEOUT_NS, TimeUnit.NANOSECONDS);
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
            notes.add("Etherware-RT: " + "RealtimeScheduler: Table II (0: OTHER, 1-3: FIFO 80/70/60), Algorithm 1;"
                    + " controller V1 " + v1.name() + " " + v1.polesRadPerS());
            notes.add(String.format(Locale.ROOT, "  controller Ticks: sent %d, skipped %d late and %d busy;"
                    + " cycles recorded %d (dropped %d); scheduler-counted deadline misses %d; DSP board late"
                    + " cycles %d", ticks.ticksSent(), ticks.skippedLate(), ticks.skippedBusy(),
                    cycles.cycles().size(), cycles.dropped(), scheduler.stats().deadlineMisses(),
                    rig.board().lateCycles()));
            notifier.threadGrant().ifPresent(grant -> notes.add("  " + grant.toLine()));
            threads.grants().forEach(grant -> notes.add("  " + grant.toLine()));
            List<ControlCycle> recorded = cycles.cycles();
            // V2's first cycle, for the CSV and for where the "after" figures start.
            long v2FromNs = recorded.stream().filter(c -> c.gainVersion() == 2).mapToLong(ControlCycle::releaseNs)
                    .min().orElse(answerNs);
            if (result != null) {
                events.add(v2FromNs, ScenarioEvent.Kind.NOTE, "V2 first cycle");
            }
            ScenarioRun run = new ScenarioRun("upgrade", "V1 → V2 upgrade", periodNs, originNs, firstReleaseNs, endNs,
                    probe.samples(), recorded, events.snapshot(), notes);
            return new UpgradeOutcome(run, result, failure, requestNs, Math.min(answerNs, v2FromNs), answerNs);
        }
    }
}
