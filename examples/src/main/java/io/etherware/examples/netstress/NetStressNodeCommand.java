package io.etherware.examples.netstress;

import io.etherware.core.kernel.DeliveryWarmUp;
import io.etherware.core.kernel.EtherwareNode;
import io.etherware.core.message.Criticality;
import io.etherware.examples.migrate.CycleReport;
import io.etherware.examples.migrate.ListenedController;
import io.etherware.examples.migrate.WarmUp;
import io.etherware.examples.scenario.ControlListeners;
import io.etherware.examples.scenario.CpuLoad;
import io.etherware.examples.scenario.GcActivity;
import io.etherware.examples.scenario.NodeProcess;
import io.etherware.examples.scenario.ScenarioEvent;
import io.etherware.examples.scenario.ScenarioEvents;
import io.etherware.examples.scenario.Schedulers;
import io.etherware.examples.stress.StressComponent;
import io.etherware.examples.stress.StressScenario;
import io.etherware.pendulum.components.DspProxy;
import io.etherware.pendulum.components.PendulumController;
import io.etherware.rt.scheduling.RealtimeScheduler;
import io.etherware.services.network.NetworkMessenger;
import io.etherware.services.notifier.Notifier;
import io.etherware.services.notifier.NotifierConfig;
import io.etherware.services.notifier.Subscription;
import io.etherware.services.notifier.SubscriptionStats;
import java.io.BufferedReader;
import java.io.InputStreamReader;
import java.io.PrintWriter;
import java.net.InetSocketAddress;
import java.nio.charset.StandardCharsets;
import java.time.Duration;
import java.util.List;
import java.util.Locale;
import java.util.concurrent.Callable;
import picocli.CommandLine.Command;
import picocli.CommandLine.Model.CommandSpec;
import picocli.CommandLine.Option;
import picocli.CommandLine.ParameterException;
import picocli.CommandLine.Spec;

/**
 * {@code etherware-demo netstress-node}: node 2 of the networked stress experiment, in a JVM of its
 * own, which {@link NetStressScenario} starts once per run. It dials the plant's node on the run's
 * scheduler and network thread policy, hosts the controller ({@link ListenedController}, its cycles
 * reported to node 1 by {@link CycleReport}) and a stress task of its own on LOW Ticks from its own
 * Notifier, and prints {@code READY} once the DSPProxy and the recorder resolve from here.
 *
 * <p>Its standard input carries the run: {@code START <firstStressNs>} (the host's monotonic
 * clock, which both JVMs share) starts the load threads and the stress Ticks; the end of input
 * stops them, and the node prints its results as lines ({@link Results}) and exits.
 *
 * <p>Run by picocli on the main thread, which then only reads its input.
 */
@Command(name = "netstress-node", hidden = true, mixinStandardHelpOptions = true,
        description = "Node 2 of the netstress scenario, started by it in a second JVM.")
public final class NetStressNodeCommand implements Callable<Integer> {

    /** The command that starts the run: {@code START <firstStressNs>}. */
    static final String START = "START";
    private static final Duration RESOLVE_TIMEOUT = Duration.ofSeconds(30);
    private static final String STRESS_TICKS = "stress";

    @Spec
    private CommandSpec spec;

    @Option(names = "--connect", required = true, paramLabel = "HOST:PORT",
            description = "The plant's node (node 1) to dial.")
    private String connect;

    @Option(names = "--listener", required = true, paramLabel = "NAME",
            description = "The control listener name the controller's configuration carries.")
    private String listener;

    @Option(names = "--variant", required = true, paramLabel = "RUN",
            description = "The run: ${COMPLETION-CANDIDATES}.")
    private StressScenario.Variant variant;

    @Option(names = "--stress-every-ms", required = true, paramLabel = "MS",
            description = "Period of the stress task's LOW Ticks.")
    private long stressEveryMs;

    @Option(names = "--stress-ms", required = true, paramLabel = "MS",
            description = "How long each stress activation computes.")
    private long stressMs;

    @Option(names = "--load-threads", required = true, paramLabel = "N",
            description = "Ordinary threads that load the cores and allocate.")
    private int loadThreads;

    @Option(names = "--rt-cpus", paramLabel = "CPUS", defaultValue = "inherit",
            description = "The CPUs of this node's real-time threads (inherit: every CPU); the JVM's other"
                    + " threads keep the affinity the JVM was started with.")
    private String rtCpus;

    @Override
    public Integer call() throws Exception {
        InetSocketAddress plant;
        try {
            plant = NodeProcess.address(connect);
        } catch (IllegalArgumentException e) {
            throw new ParameterException(spec.commandLine(), "--connect=" + e.getMessage());
        }
        if (stressEveryMs < 1 || stressMs < 1 || stressMs >= stressEveryMs || loadThreads < 0 || loadThreads > 256) {
            throw new ParameterException(spec.commandLine(), "--stress-every-ms=" + stressEveryMs + ", --stress-ms="
                    + stressMs + ", --load-threads=" + loadThreads + ": need 1 <= stress-ms < stress-every-ms and"
                    + " 0..256 load threads");
        }
        PrintWriter err = spec.commandLine().getErr();
        err.println("netstress-node: " + NetStressScenario.CONTROL_NODE + " (" + variant.title() + ") dialing " + plant);
        err.flush();
        PrintWriter out = spec.commandLine().getOut();
        io.etherware.rt.platform.CpuSet realtimeCpus;
        try {
            realtimeCpus = io.etherware.rt.platform.CpuSet.parse(rtCpus);
        } catch (IllegalArgumentException e) {
            throw new ParameterException(spec.commandLine(), "--rt-cpus=" + e.getMessage());
        }
        RealtimeScheduler realtime = variant == StressScenario.Variant.RT ? Schedulers.etherwareRt(realtimeCpus) : null;
        ScenarioEvents events = new ScenarioEvents();
        GcActivity gcBefore = GcActivity.now();
        try (var node = EtherwareNode.builder().nodeId(NetStressScenario.CONTROL_NODE)
                .scheduler(() -> realtime != null ? realtime : Schedulers.original()).build().start();
                var net = NetworkMessenger.start(node, NetStressScenario.network(variant,
                        WarmUp.warmedCodec(node), realtimeCpus).peer(plant).build());
                ControlListeners.Registration registration = ControlListeners.register(listener,
                        CycleReport.forwarder(node))) {
            DeliveryWarmUp.run(node); // before real time depends on it, as node 1 does
            node.add(PendulumController.DEFAULT_PROFILE,
                    () -> new ListenedController(ListenedController.configuration(listener)));
            node.add(NetStressScenario.NODE2_STRESS, () -> new StressComponent(stressMs * 1_000_000L, events));
            // Node 2's own Notifier, SCHED_FIFO 82 in both runs as on node 1, for its stress task's Ticks.
            Notifier notifier = Notifier.install(node, NotifierConfig.defaults().withCpus(realtimeCpus));
            for (var profile : List.of(DspProxy.DEFAULT_PROFILE, CycleReport.RECORDER)) {
                if (!net.awaitResolvable(profile, RESOLVE_TIMEOUT)) {
                    err.println("netstress-node: " + profile + " does not resolve from " + node.nodeId() + " within "
                            + RESOLVE_TIMEOUT.toSeconds() + " s");
                    err.flush();
                    return 1;
                }
            }
            out.println(NodeProcess.READY);
            out.flush();

            CpuLoad load = CpuLoad.start(0);
            boolean started = false;
            var in = new BufferedReader(new InputStreamReader(System.in, StandardCharsets.UTF_8));
            try {
                for (String line = in.readLine(); line != null; line = in.readLine()) {
                    String[] words = line.strip().split(" ");
                    if (!started && words.length == 2 && words[0].equals(START)) {
                        started = true;
                        notifier.subscribe(Subscription.periodic(STRESS_TICKS, NetStressScenario.NODE2_STRESS,
                                Criticality.LOW, stressEveryMs * 1_000_000L).startingAt(Long.parseLong(words[1])));
                        load = CpuLoad.start(loadThreads);
                    } else {
                        err.println("netstress-node: ignoring input '" + line + "'");
                        err.flush();
                    }
                }
            } finally {
                load.close();
            }
            SubscriptionStats stressTicks = notifier.unsubscribe(STRESS_TICKS).orElse(null);
            GcActivity gc = GcActivity.now().since(gcBefore);
            List<ScenarioEvent> marks = events.snapshot();
            var results = new Results.Writer(out);
            marks.forEach(results::event);
            results.misses(realtime != null ? realtime.stats().deadlineMisses() : Results.NOT_COUNTED);
            results.note(String.format(Locale.ROOT, "  node 2: stress Ticks sent %d, activations %d; load: %d threads"
                    + " allocated %.1f GiB; GC: %d collections, %d ms; network threads %s",
                    stressTicks != null ? stressTicks.ticksSent() : 0,
                    marks.stream().filter(e -> e.kind() == ScenarioEvent.Kind.STRESS_START).count(),
                    load.threadCount(), load.allocatedBytes() / (double) (1L << 30), gc.collections(), gc.timeMs(),
                    net.ioThreadPolicy()));
            if (realtime != null) {
                results.note(StressScenario.realtimeNote(realtime).replaceFirst("^  ", "  node 2: "));
                realtime.platformReport().threads().forEach(grant -> results.note("  node 2: " + grant.toLine()));
            }
            notifier.threadGrant().ifPresent(grant -> results.note("  node 2: " + grant.toLine()));
            out.flush();
        }
        return 0;
    }
}
