package io.etherware.examples.netstress;

import io.etherware.examples.scenario.Progress;
import io.etherware.examples.scenario.RunSummary;
import io.etherware.examples.scenario.ScenarioOptions;
import io.etherware.examples.stress.StressConfig;
import io.etherware.examples.stress.StressOptions;
import io.etherware.examples.stress.StressScenario;
import java.io.PrintWriter;
import java.nio.file.Path;
import java.util.ArrayList;
import java.util.List;
import java.util.concurrent.Callable;
import picocli.CommandLine.Command;
import picocli.CommandLine.Mixin;
import picocli.CommandLine.Model.CommandSpec;
import picocli.CommandLine.Option;
import picocli.CommandLine.ParameterException;
import picocli.CommandLine.Spec;

/**
 * {@code etherware-demo netstress}: the stress experiment of paper Section VI-B across two nodes
 * in two JVMs (the topology of Fig. 10), once on the original Etherware and once on
 * Etherware-RT, then the table, the CSVs and the plots.
 *
 * <p>Run by picocli on the main thread.
 */
@Command(name = "netstress", mixinStandardHelpOptions = true, sortOptions = false,
        modelTransformer = ScenarioOptions.DurationHelp.class,
        header = "Networked control under computational stress on both nodes, original Etherware vs Etherware-RT.",
        description = {
            "The stress experiment (paper Section VI-B) in the two-node topology of Fig. 10: node 1 (this JVM) holds"
                    + " the DSP board, the DSPProxy and the Notifier, node 2 (a second JVM it starts per run) the"
                    + " controller, so every control cycle crosses TCP on loopback twice. Each node runs a stress task"
                    + " on LOW Ticks (node 2's half a stress period after node 1's) and ordinary load threads. Twice: on the original Etherware (one FIFO dispatcher"
                    + " and ordinary network threads on both nodes) and on Etherware-RT (Table II dispatchers and"
                    + " SCHED_FIFO network threads, the lane of HIGH messages above the HIGH dispatcher). Prints a side-by-side table and writes"
                    + " CSVs and PNG/SVG plots.",
            "Default: 20 s per run."},
        footer = {"", "Example: etherware-demo netstress --duration 30 --out /tmp/netstress"})
public final class NetStressCommand implements Callable<Integer> {

    @Spec
    private CommandSpec spec;

    @Mixin
    private ScenarioOptions common = new ScenarioOptions(StressOptions.DURATION);

    @Mixin
    private StressOptions stress;

    @Option(names = "--node2-offset", paramLabel = "SECONDS",
            description = "How long after node 1's stress node 2's comes (default: half of --stress-every; 0: both"
                    + " at once, which on a host with as many cores as nodes holds every core at SCHED_FIFO and"
                    + " meets the kernel's real-time throttling).")
    private Double node2OffsetS;

    @Override
    public Integer call() throws Exception {
        StressConfig config = stress.config(spec.commandLine(), common, "netstress");
        long offsetNs = node2OffsetS == null ? NetStressScenario.defaultNode2OffsetNs(config)
                : Math.round(node2OffsetS * 1e9);
        if (offsetNs < 0 || offsetNs >= config.stressEveryNs()) {
            throw new ParameterException(spec.commandLine(), "--node2-offset=" + node2OffsetS + " is out of range:"
                    + " from 0 to below --stress-every (" + config.stressEveryNs() / 1e9 + " s)");
        }
        PrintWriter out = spec.commandLine().getOut();
        out.println(NetStressReport.heading(config, offsetNs));
        out.flush();

        var scenario = new NetStressScenario(config, offsetNs,
                label -> Progress.onStandardError(label, config.durationNs() / 1e9));
        spec.commandLine().getErr().println("warming up: each variant briefly on both nodes, without load or stress");
        spec.commandLine().getErr().flush();
        scenario.warmUp();
        List<NetStressRun> runs = new ArrayList<>();
        for (StressScenario.Variant variant : StressScenario.Variant.values()) {
            if (stress.runs(variant)) {
                runs.add(scenario.run(variant));
            }
        }
        List<RunSummary> summaries = runs.stream().map(run -> RunSummary.of(run.run())).toList();
        List<Path> written = NetStressReport.write(config, offsetNs, runs, summaries);

        out.println();
        out.print(NetStressReport.table(runs, summaries));
        out.println();
        runs.forEach(run -> run.run().notes().forEach(out::println));
        out.println();
        out.println("Wrote:");
        written.forEach(path -> out.println("  " + path.toAbsolutePath().normalize()));
        out.flush();
        return 0;
    }
}
