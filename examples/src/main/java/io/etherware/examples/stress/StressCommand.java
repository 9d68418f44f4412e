package io.etherware.examples.stress;

import io.etherware.examples.scenario.Progress;
import io.etherware.examples.scenario.RunSummary;
import io.etherware.examples.scenario.ScenarioOptions;
import io.etherware.examples.scenario.ScenarioRun;
import io.etherware.examples.output.ComparisonTable;
import java.io.PrintWriter;
import java.nio.file.Path;
import java.util.ArrayList;
import java.util.List;
import java.util.concurrent.Callable;
import picocli.CommandLine.Command;
import picocli.CommandLine.Mixin;
import picocli.CommandLine.Model.CommandSpec;
import picocli.CommandLine.Spec;

/**
 * {@code etherware-demo stress}: the stress experiment of paper Section VI-B, once on the original
 * Etherware and once on Etherware-RT, then the table, the CSVs and the plots.
 *
 * <p>Run by picocli on the main thread.
 */
@Command(name = "stress", mixinStandardHelpOptions = true, sortOptions = false,
        modelTransformer = ScenarioOptions.DurationHelp.class,
        header = "Periodic control under computational stress, original Etherware vs Etherware-RT (Section VI-B).",
        description = {
            "Balance the pendulum under computational stress (paper Section VI-B, Fig. 7 and 9), twice: on the"
                    + " original Etherware (one FIFO dispatcher) and on Etherware-RT (Table II dispatchers at"
                    + " SCHED_FIFO priorities, Algorithm 1). The controller runs on HIGH Ticks every period; a stress"
                    + " task on LOW Ticks computes for about a second every few seconds; ordinary threads load"
                    + " every core and allocate. Prints a side-by-side table and writes CSVs and PNG/SVG plots.",
            "Default: 20 s per run."},
        footer = {"", "Example: etherware-demo stress --duration 30 --out /tmp/stress"})
public final class StressCommand implements Callable<Integer> {

    /** Default run length, seconds. */
    public static final double DEFAULT_DURATION_S = StressConfig.DEFAULT_DURATION_NS / 1e9;

    @Spec
    private CommandSpec spec;

    @Mixin
    private ScenarioOptions common = new ScenarioOptions(StressOptions.DURATION);

    @Mixin
    private StressOptions stress;

    @Override
    public Integer call() throws Exception {
        StressConfig config = stress.config(spec.commandLine(), common, "stress");
        PrintWriter out = spec.commandLine().getOut();
        out.println(StressReport.heading(config));
        out.flush();

        var scenario = new StressScenario(config, label -> Progress.onStandardError(label, config.durationNs() / 1e9));
        spec.commandLine().getErr().println("warming up: each variant briefly, without load or stress");
        spec.commandLine().getErr().flush();
        scenario.warmUp();
        List<ScenarioRun> runs = new ArrayList<>();
        for (StressScenario.Variant variant : StressScenario.Variant.values()) {
            if (stress.runs(variant)) {
                runs.add(scenario.run(variant));
            }
        }
        List<RunSummary> summaries = runs.stream().map(RunSummary::of).toList();
        List<Path> written = StressReport.write(config, runs, summaries);

        out.println();
        out.print(ComparisonTable.format(runs, summaries));
        out.println();
        runs.forEach(run -> run.notes().forEach(out::println));
        out.println();
        out.println("Wrote:");
        written.forEach(path -> out.println("  " + path.toAbsolutePath().normalize()));
        out.flush();
        return 0;
    }
}
