package io.etherware.examples;

import io.etherware.deploy.Launcher;
import io.etherware.examples.bench.BenchCommand;
import io.etherware.examples.migrate.ControlNodeCommand;
import io.etherware.examples.serial.DspBoardCommand;
import io.etherware.examples.migrate.MigrateCommand;
import io.etherware.examples.netstress.NetStressCommand;
import io.etherware.examples.netstress.NetStressNodeCommand;
import io.etherware.examples.stress.StressCommand;
import io.etherware.examples.upgrade.UpgradeCommand;
import java.util.Map;
import picocli.CommandLine;
import picocli.CommandLine.Command;
import picocli.CommandLine.Model.CommandSpec;
import picocli.CommandLine.ParameterException;
import picocli.CommandLine.Spec;

/**
 * {@code etherware-demo}: the paper's experiments as one-command scenarios (Section VI-B and
 * VI-C). Each scenario is a subcommand with {@code --duration}, {@code --period-ms}, {@code --out}
 * and {@code --help}; it prints a progress line on standard error while it runs, then its table
 * and the files it wrote on standard output.
 *
 * <pre>
 * ./mvnw -q -pl examples -am -DskipTests package exec:exec@stress -Dscenario.args="--duration 30"
 * java -jar examples/target/examples-0.1.0-SNAPSHOT.jar stress --help
 * </pre>
 *
 * <p>Runs on the main thread; the scenarios start and stop their own threads.
 */
@Command(name = "etherware-demo", mixinStandardHelpOptions = true, versionProvider = EtherwareDemo.Version.class,
        description = "The Etherware paper's experiments on a simulated inverted pendulum.",
        subcommands = {StressCommand.class, NetStressCommand.class, UpgradeCommand.class, MigrateCommand.class,
            BenchCommand.class, DspBoardCommand.class, Launcher.class, ControlNodeCommand.class, NetStressNodeCommand.class,
            CommandLine.HelpCommand.class},
        footer = {"", "Plots and CSVs go to target/scenarios/<scenario>/ unless --out says otherwise;"
                + " the bench writes target/bench/report.md and report.json."})
public final class EtherwareDemo implements Runnable {

    @Spec
    private CommandSpec spec;

    /** Exits with the command's code: 0 done, 1 failed, 2 a usage error. */
    public static void main(String[] args) {
        System.exit(commandLine().execute(args));
    }

    /** The command line, configured as {@link #main} uses it (headless plots, case-insensitive run names). */
    public static CommandLine commandLine() {
        System.setProperty("java.awt.headless", "true");
        return new CommandLine(new EtherwareDemo()).setCaseInsensitiveEnumValuesAllowed(true);
    }

    @Override
    public void run() {
        throw new ParameterException(spec.commandLine(), "Name a scenario: " + String.join(", ",
                spec.subcommands().entrySet().stream()
                .filter(e -> !e.getKey().equals("help") && !e.getValue().getCommandSpec().usageMessage().hidden())
                .map(Map.Entry::getKey).toList()));
    }

    /** The version from the jar's manifest, or "development build" when run from classes. */
    static final class Version implements CommandLine.IVersionProvider {
        @Override
        public String[] getVersion() {
            String version = EtherwareDemo.class.getPackage().getImplementationVersion();
            return new String[] {"etherware-demo " + (version != null ? version : "(development build)")};
        }
    }
}
