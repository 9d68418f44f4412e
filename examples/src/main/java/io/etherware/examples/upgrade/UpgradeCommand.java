package io.etherware.examples.upgrade;

import io.etherware.examples.EtherwareDemo;
import io.etherware.examples.scenario.Progress;
import io.etherware.examples.scenario.ScenarioOptions;
import java.io.IOException;
import java.io.PrintWriter;
import java.net.URISyntaxException;
import java.nio.file.Files;
import java.nio.file.Path;
import java.util.List;
import java.util.concurrent.Callable;
import java.util.stream.Stream;
import picocli.CommandLine.Command;
import picocli.CommandLine.Mixin;
import picocli.CommandLine.Model.CommandSpec;
import picocli.CommandLine.Option;
import picocli.CommandLine.ParameterException;
import picocli.CommandLine.Spec;

/**
 * {@code etherware-demo upgrade}: the runtime controller upgrade of paper Section VI-C1, then the
 * table, the CSV and the plot.
 *
 * <p>Run by picocli on the main thread.
 */
@Command(name = "upgrade", mixinStandardHelpOptions = true, sortOptions = false,
        modelTransformer = ScenarioOptions.DurationHelp.class,
        header = "Replace the controller V1 by V2 from a plugin jar while it balances (Section VI-C1).",
        description = {
            "Replace the pendulum's controller while it balances (paper Section VI-C1, Fig. 10 and 11): V1 (soft"
                    + " gains) runs on Etherware-RT; at --upgrade-at a HIGH management request makes the node load"
                    + " V2 (tight gains) from a plugin jar and swap it in at a message boundary, with V1's state."
                    + " Prints V1 against V2, the upgrade's timings and the control hand-over; writes a CSV and"
                    + " PNG/SVG plots.",
            "Default: 60 s, upgrade at 30 s."},
        footer = {"", "Example: etherware-demo upgrade --duration 20 --upgrade-at 8 --remote"})
public final class UpgradeCommand implements Callable<Integer> {

    @Spec
    private CommandSpec spec;

    /** {@code --duration}: 60 s by default, at least a second of each controller version. */
    static final ScenarioOptions.DurationRule DURATION = new ScenarioOptions.DurationRule(
            UpgradeConfig.DEFAULT_DURATION_NS / 1e9, UpgradeConfig.MIN_DURATION_NS / 1e9,
            UpgradeConfig.MIN_PHASE_NS / 1_000_000_000L + " s of V1 before the upgrade and as much of V2 after it");

    @Mixin
    private ScenarioOptions common = new ScenarioOptions(DURATION);

    @Option(names = "--upgrade-at", paramLabel = "SECONDS",
            description = "When the management request asks for V2, in seconds after the start (default: 30, or"
                    + " half the duration if shorter).")
    private Double upgradeAtS;

    @Option(names = "--jar", paramLabel = "PATH",
            description = "The plugin jar with controller V2 (default: the build's, target/plugins/*"
                    + UpgradeConfig.JAR_SUFFIX + ").")
    private Path jar;

    @Option(names = "--remote",
            description = "The paper's topology (Fig. 10): the controller on node 2 in a second JVM, upgraded by a"
                    + " request from the Requester component on node 1 (default: one node).")
    private boolean remote;

    @Override
    public Integer call() throws Exception {
        UpgradeConfig config = config();
        PrintWriter out = spec.commandLine().getOut();
        out.println(UpgradeReport.heading(config));
        out.flush();

        UpgradeOutcome outcome = new UpgradeScenario(config,
                Progress.onStandardError("upgrade", config.durationNs() / 1e9)).run();
        List<Path> written = UpgradeReport.write(config, outcome);

        UpgradeReport.report(config, outcome).print(out, written);
        return outcome.upgraded() ? 0 : 1;
    }

    private UpgradeConfig config() throws IOException {
        long durationNs = common.durationNs();
        Path plugin = jar != null ? jar : defaultJar();
        if (!Files.isRegularFile(plugin)) {
            throw new ParameterException(spec.commandLine(), "--jar=" + plugin + " is not a file: give the plugin jar"
                    + " with controller V2, or build it with ./mvnw -pl examples -am -DskipTests package");
        }
        UpgradeConfig config = UpgradeConfig.of(durationNs, common.periodNs(), plugin, common.out("upgrade"))
                .withBaudRate(common.baudRate()).withRemote(remote);
        if (upgradeAtS != null) {
            long atNs = Math.round(upgradeAtS * 1e9);
            if (!(atNs >= UpgradeConfig.MIN_PHASE_NS && atNs <= durationNs - UpgradeConfig.MIN_PHASE_NS)) {
                throw new ParameterException(spec.commandLine(), "--upgrade-at=" + upgradeAtS + " is out of range:"
                        + " leave at least 1 s before it and 1 s after it within --duration (" + durationNs / 1e9
                        + " s)");
            }
            config = config.withUpgradeAtNs(atNs);
        }
        return config;
    }

    /**
     * The plugin jar the build put next to these classes: {@code target/plugins} beside
     * {@code target/classes} (exec, tests) or beside the examples jar (java -jar).
     */
    static Path defaultJar() throws IOException {
        Path plugins;
        try {
            Path location = Path.of(EtherwareDemo.class.getProtectionDomain().getCodeSource().getLocation().toURI());
            plugins = location.getParent().resolve("plugins");
        } catch (URISyntaxException | RuntimeException e) {
            plugins = Path.of("target", "plugins");
        }
        if (Files.isDirectory(plugins)) {
            try (Stream<Path> files = Files.list(plugins)) {
                return files.filter(f -> f.getFileName().toString().endsWith(UpgradeConfig.JAR_SUFFIX)).sorted()
                        .findFirst().orElse(plugins.resolve("examples" + UpgradeConfig.JAR_SUFFIX));
            }
        }
        return plugins.resolve("examples" + UpgradeConfig.JAR_SUFFIX);
    }
}
