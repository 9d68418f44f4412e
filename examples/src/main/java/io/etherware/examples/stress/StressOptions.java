package io.etherware.examples.stress;

import io.etherware.examples.scenario.ScenarioOptions;
import io.etherware.rt.platform.CpuSet;
import java.util.stream.IntStream;
import picocli.CommandLine;
import picocli.CommandLine.Option;
import picocli.CommandLine.ParameterException;

/**
 * The stress experiment's command-line options, shared by {@code stress} and {@code netstress}
 * (a picocli mixin): the stress task's period and work, the load threads, and which run.
 * Validated by {@link #config}, whose messages name the option and its range.
 */
public final class StressOptions {

    /** {@code --duration} of {@code stress} and {@code netstress}: 20 s per run by default. */
    public static final ScenarioOptions.DurationRule DURATION =
            ScenarioOptions.DurationRule.withDefault(StressConfig.DEFAULT_DURATION_NS / 1e9);

    @Option(names = "--stress-every", paramLabel = "SECONDS", defaultValue = "5",
            description = "Period of the stress task's LOW Ticks in seconds (default: ${DEFAULT-VALUE}).")
    private double stressEveryS;

    @Option(names = "--stress-ms", paramLabel = "MS", defaultValue = "1000",
            description = "How long each stress activation computes, in milliseconds (default: ${DEFAULT-VALUE}).")
    private long stressMs;

    @Option(names = "--load-threads", paramLabel = "N",
            description = "Ordinary threads that load the cores and allocate (default: one per core).")
    private Integer loadThreads;

    @Option(names = "--rt-cpus", paramLabel = "CPUS",
            description = "Partition the CPUs: every real-time thread (dispatchers, Notifier, network threads, the"
                    + " board) on CPUS (e.g. 1), every other thread of the JVM(s) on the rest, in both runs (default:"
                    + " no partition). Keep --stress-ms below the kernel's real-time budget (sched_rt_runtime_us,"
                    + " 950 ms a second): on one CPU a longer stress task is throttled with every real-time thread there.")
    private String rtCpus;

    @Option(names = "--only", paramLabel = "RUN",
            description = "Run only one of: ${COMPLETION-CANDIDATES} (default: both, FIFO first).")
    private StressScenario.Variant only;

    /** Whether {@code variant} is to run. */
    public boolean runs(StressScenario.Variant variant) {
        return only == null || only == variant;
    }

    /**
     * The configuration these options and {@code common} give, writing to {@code scenario}'s
     * default directory unless {@code --out} says otherwise.
     *
     * @throws ParameterException naming the option, if one is out of range or the output directory unusable
     */
    public StressConfig config(CommandLine commandLine, ScenarioOptions common, String scenario) {
        if (!(stressEveryS > 0 && stressEveryS <= 3_600)) {
            throw new ParameterException(commandLine, "--stress-every=" + stressEveryS
                    + " is out of range: give the stress period in seconds, above 0 and at most 3600");
        }
        long stressEveryNs = Math.round(stressEveryS * 1e9);
        if (stressMs < 1 || stressMs * 1_000_000L >= stressEveryNs || stressMs > 10_000) {
            throw new ParameterException(commandLine, "--stress-ms=" + stressMs + " is out of range: from 1 to"
                    + " 10000 ms and shorter than --stress-every (" + stressEveryS + " s)");
        }
        int threads = loadThreads != null ? loadThreads : Runtime.getRuntime().availableProcessors();
        if (threads < 0 || threads > 256) {
            throw new ParameterException(commandLine, "--load-threads=" + threads
                    + " is out of range: from 0 (no load) to 256");
        }
        long periodNs = common.periodNs();
        if (stressEveryNs < periodNs) {
            throw new ParameterException(commandLine, "--stress-every=" + stressEveryS
                    + " s is shorter than the control period --period-ms");
        }
        CpuSet realtimeCpus = CpuSet.inherit();
        if (rtCpus != null) {
            try {
                realtimeCpus = CpuSet.parse(rtCpus);
            } catch (IllegalArgumentException e) {
                throw new ParameterException(commandLine, "--rt-cpus=" + e.getMessage());
            }
            int cpus = Runtime.getRuntime().availableProcessors();
            if (!realtimeCpus.isInherit() && IntStream.range(0, cpus).allMatch(realtimeCpus::contains)) {
                throw new ParameterException(commandLine, "--rt-cpus=" + rtCpus + " leaves no CPU for the"
                        + " JVM's other threads: name fewer CPUs (this machine has " + cpus + ")");
            }
        }
        return StressConfig.defaults(common.out(scenario))
                .withDurationNs(common.durationNs())
                .withPeriodNs(periodNs)
                .withStress(stressEveryNs, stressMs * 1_000_000L)
                .withLoadThreads(threads)
                .withBaudRate(common.baudRate())
                .withRealtimeCpus(realtimeCpus);
    }
}
