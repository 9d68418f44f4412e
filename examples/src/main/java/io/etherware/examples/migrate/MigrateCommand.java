package io.etherware.examples.migrate;

import io.etherware.examples.scenario.Progress;
import io.etherware.examples.scenario.ScenarioOptions;
import java.io.PrintWriter;
import java.nio.file.Path;
import java.util.List;
import java.util.concurrent.Callable;
import picocli.CommandLine.Command;
import picocli.CommandLine.Mixin;
import picocli.CommandLine.Model.CommandSpec;
import picocli.CommandLine.Option;
import picocli.CommandLine.ParameterException;
import picocli.CommandLine.Spec;

/**
 * {@code etherware-demo migrate}: the runtime controller migration of paper Section VI-C2 across
 * two JVMs, then the table, the CSV and the plot.
 *
 * <p>Run by picocli on the main thread.
 */
@Command(name = "migrate", mixinStandardHelpOptions = true, sortOptions = false,
        modelTransformer = ScenarioOptions.DurationHelp.class,
        header = "Move the controller to another node while it balances (Section VI-C2), across two JVMs.",
        description = {
            "Move the pendulum's controller between nodes while it balances (paper Section VI-C2, Fig. 10 and 12):"
                    + " node 1 (this JVM) holds the DSP board and the DSPProxy, node 2 (a second JVM it starts) the"
                    + " controller. At --migrate-at a HIGH management request asks node 2 to move the controller to"
                    + " node 1; its state travels as XML and the messages meanwhile are held and forwarded. Prints"
                    + " node 2 against node 1, the migration's timings and the control hand-over; writes a CSV and"
                    + " PNG/SVG plots.",
            "Default: 60 s, migration at 40 s."},
        footer = {"", "Example: etherware-demo migrate --duration 20 --migrate-at 12"})
public final class MigrateCommand implements Callable<Integer> {

    @Spec
    private CommandSpec spec;

    /** {@code --duration}: 60 s by default, at least 2 s on each node. */
    static final ScenarioOptions.DurationRule DURATION = new ScenarioOptions.DurationRule(
            MigrateConfig.DEFAULT_DURATION_NS / 1e9, MigrateConfig.MIN_DURATION_NS / 1e9,
            MigrateConfig.MIN_PHASE_NS / 1_000_000_000L
                    + " s on node 2 before the migration and as much on node 1 after it");

    @Mixin
    private ScenarioOptions common = new ScenarioOptions(DURATION);

    @Option(names = "--migrate-at", paramLabel = "SECONDS",
            description = "When the requester asks for the migration, in seconds after the start (default: 40, or"
                    + " two thirds of the duration if shorter, and no later than 2 s before the end).")
    private Double migrateAtS;

    @Override
    public Integer call() throws Exception {
        MigrateConfig config = config();
        PrintWriter out = spec.commandLine().getOut();
        out.println(MigrateReport.heading(config));
        out.flush();

        MigrateOutcome outcome = new MigrateScenario(config,
                Progress.onStandardError("migrate", config.durationNs() / 1e9)).run();
        List<Path> written = MigrateReport.write(config, outcome);

        MigrateReport.report(config, outcome).print(out, written);
        return outcome.migrated() ? 0 : 1;
    }

    /** The run's settings; every option is checked here, in option terms, before the config sees it. */
    private MigrateConfig config() {
        long durationNs = common.durationNs();
        MigrateConfig config = MigrateConfig.of(durationNs, common.periodNs(), common.out("migrate"))
                .withBaudRate(common.baudRate());
        if (migrateAtS != null) {
            long atNs = Math.round(migrateAtS * 1e9);
            if (!(atNs >= MigrateConfig.MIN_PHASE_NS && atNs <= durationNs - MigrateConfig.MIN_PHASE_NS)) {
                throw new ParameterException(spec.commandLine(), "--migrate-at=" + migrateAtS + " is out of range:"
                        + " leave at least 2 s before it and 2 s after it within --duration (" + durationNs / 1e9
                        + " s)");
            }
            config = config.withMigrateAtNs(atNs);
        }
        return config;
    }
}
