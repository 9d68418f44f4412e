package io.etherware.examples.bench;

import io.etherware.examples.output.OutputDirectory;
import io.etherware.rt.platform.CpuLatencyHold;
import java.io.PrintWriter;
import java.nio.file.Path;
import java.util.ArrayList;
import java.util.List;
import java.util.Set;
import java.util.concurrent.Callable;
import java.util.stream.Collectors;
import picocli.CommandLine.Command;
import picocli.CommandLine.Model.CommandSpec;
import picocli.CommandLine.Option;
import picocli.CommandLine.ParameterException;
import picocli.CommandLine.Spec;

/**
 * {@code etherware-demo bench}: Etherware-RT beside its baselines in one JVM (plus
 * {@code cyclictest} when installed); prints a markdown table and writes {@code report.md} and
 * {@code report.json} under {@code --out}.
 *
 * <p>Run by picocli on the main thread.
 */
@Command(name = "bench", mixinStandardHelpOptions = true, sortOptions = false,
        header = "Latency, throughput and cost of Etherware-RT beside its baselines.",
        description = {
            "Measures, one after another in this JVM: 1 kHz periodic lateness (Notifier, ScheduledThreadPoolExecutor,"
                    + " cyclictest) idle and loaded; HIGH dispatch latency (FIFO, real-time scheduler, bare queue)"
                    + " idle and under a LOW flood; throughput between two components; the XML codec beside Jackson"
                    + " JSON; a loopback request/reply beside raw TCP; the upgrade gap; the collector's pauses.",
            "Default: 60 s per periodic row, about 10 minutes in all; --quick takes about 30 s."},
        footer = {"", "Example: etherware-demo bench --duration 20 --out /tmp/bench"})
public final class BenchCommand implements Callable<Integer> {

    @Spec
    private CommandSpec spec;

    @Option(names = "--duration", paramLabel = "SECONDS",
            description = "Length of each periodic-lateness row in seconds (default: 60; from 1 to 3600).")
    private Double durationS;

    @Option(names = "--quick", description = "About 30 s in all: checks the harness, not the figures.")
    private boolean quick;

    @Option(names = "--repetitions", paramLabel = "N",
            description = "Upgrades measured for the upgrade gap (default: 200; 20 with --quick; at least 5).")
    private Integer repetitions;

    @Option(names = "--section", paramLabel = "N", split = ",",
            description = "Run only these sections, 1 to 6, e.g. --section 2,5 (default: all; the collector's"
                    + " pauses, section 7, are always reported).")
    private List<Integer> onlySections = new ArrayList<>();

    @Option(names = "--cpus-may-sleep",
            description = "Do not hold /dev/cpu_dma_latency at 0 during the run (default: held where permitted, for"
                    + " every row alike, as cyclictest holds it; the report says which).")
    private boolean cpusMaySleep;

    @Option(names = "--out", paramLabel = "DIR", defaultValue = "target/bench",
            description = "Directory for report.md and report.json (default: ${DEFAULT-VALUE}).")
    private Path out;

    /** {@code --duration}'s name until the bench took the scenarios' name for it; kept so old command lines run. */
    @Option(names = "--duration-s", paramLabel = "SECONDS", hidden = true)
    private Double oldDurationS;

    @Override
    public Integer call() throws Exception {
        BenchConfig config = config();
        String settings = (quick ? "--quick" : "--duration " + (durationS == null ? BenchConfig.DEFAULT_PERIODIC_S
                : durationS)) + (repetitions == null ? "" : " --repetitions " + repetitions) + (onlySections.isEmpty() ? "" : " --section " + onlySections.stream()
                .map(String::valueOf).collect(Collectors.joining(",")));
        BenchReport report;
        try (CpuLatencyHold hold = cpusMaySleep ? CpuLatencyHold.none() : CpuLatencyHold.request()) {
            report = new Bench(config, Set.copyOf(onlySections), settings + "; " + hold.state(),
                    spec.commandLine().getErr()).run();
        }
        report.write(out);
        PrintWriter stdout = spec.commandLine().getOut();
        stdout.print(report.markdown());
        stdout.println();
        stdout.println("wrote " + out.resolve(BenchReport.MARKDOWN_FILE) + " and " + out.resolve(BenchReport.JSON_FILE));
        stdout.flush();
        return 0;
    }

    private BenchConfig config() {
        if (oldDurationS != null) {
            if (durationS != null) {
                throw new ParameterException(spec.commandLine(), "--duration-s is the old name of --duration: give one");
            }
            durationS = oldDurationS;
        }
        if (quick && durationS != null) {
            throw new ParameterException(spec.commandLine(), "--duration=" + durationS + " with --quick: choose one");
        }
        for (int section : onlySections) {
            if (section < 1 || section > 6) {
                throw new ParameterException(spec.commandLine(), "--section=" + section + " is out of range: use 1 to 6");
            }
        }
        if (durationS != null && !(durationS >= 1 && durationS <= 3600)) {
            throw new ParameterException(spec.commandLine(), "--duration=" + durationS
                    + " is out of range: use 1 to 3600 seconds");
        }
        OutputDirectory.requireUsable(spec.commandLine(), "--out", out);
        if (repetitions != null && (repetitions < 5 || repetitions > 100_000)) {
            throw new ParameterException(spec.commandLine(), "--repetitions=" + repetitions
                    + " is out of range: use 5 to 100000");
        }
        BenchConfig config = quick ? BenchConfig.quick() : BenchConfig.full(durationS == null
                ? BenchConfig.DEFAULT_PERIODIC_S : durationS);
        config = config.withHoldCpuLatency(!cpusMaySleep);
        return repetitions == null ? config : config.withUpgradeRepetitions(repetitions);
    }
}
