package io.etherware.examples.scenario;

import io.etherware.examples.output.OutputDirectory;
import java.math.BigDecimal;
import java.nio.file.Path;
import java.util.ListResourceBundle;
import java.util.concurrent.TimeUnit;
import picocli.CommandLine.IModelTransformer;
import picocli.CommandLine.Model.CommandSpec;
import picocli.CommandLine.Option;
import picocli.CommandLine.ParameterException;
import picocli.CommandLine.Spec;

/**
 * The options every scenario takes ({@code --duration}, {@code --period-ms}, {@code --baud}, {@code --out}), as a
 * picocli mixin. Each scenario gives its own {@link DurationRule}; a command that names
 * {@link DurationHelp} as its model transformer shows that rule in its {@code --duration} help.
 *
 * <p>Filled in by picocli on the command's thread; not thread-safe.
 */
public final class ScenarioOptions {

    /** Longest run accepted, seconds. */
    public static final double MAX_DURATION_S = 3_600.0;
    /** Shortest run accepted where the scenario needs no more, seconds. */
    public static final double MIN_DURATION_S = 1.0;

    /**
     * What {@code --duration} means in one scenario.
     *
     * @param defaultS  the length of a run when {@code --duration} is not given, seconds
     * @param minS      the shortest run the scenario can do, seconds
     * @param minReason why it can do no shorter, as the help and the error say it (empty: no more
     *                  than the general minimum)
     */
    public record DurationRule(double defaultS, double minS, String minReason) {

        public DurationRule {
            if (!(minS >= MIN_DURATION_S && minS <= defaultS && defaultS <= MAX_DURATION_S)) {
                throw new IllegalArgumentException("minS=" + minS + ", defaultS=" + defaultS + ": must satisfy "
                        + MIN_DURATION_S + " <= minS <= defaultS <= " + MAX_DURATION_S);
            }
            minReason = minReason == null ? "" : minReason;
        }

        /** The general range, from 1 s, with the default {@code defaultS}. */
        public static DurationRule withDefault(double defaultS) {
            return new DurationRule(defaultS, MIN_DURATION_S, "");
        }

        /** The {@code --duration} help line. */
        String help() {
            return "Length of each run in seconds (default: " + seconds(defaultS) + "; at least " + seconds(minS)
                    + (minReason.isEmpty() ? "" : ": " + minReason) + "; at most " + seconds(MAX_DURATION_S) + ").";
        }
    }

    /**
     * Puts the scenario's {@link DurationRule} into its {@code --duration} help; name it as the
     * command's {@code modelTransformer}. The option comes from this mixin, the same for every
     * scenario, so picocli is handed the command's own text the way it takes translated ones: a
     * resource bundle with the option's key.
     */
    public static final class DurationHelp implements IModelTransformer {
        @Override
        public CommandSpec transform(CommandSpec command) {
            ScenarioOptions options = command.mixins().values().stream().map(CommandSpec::userObject)
                    .filter(ScenarioOptions.class::isInstance).map(ScenarioOptions.class::cast).findFirst()
                    .orElseThrow(() -> new IllegalStateException(command.name() + " has no ScenarioOptions mixin"));
            String help = options.durationRule.help();
            command.resourceBundle(new ListResourceBundle() {
                @Override
                protected Object[][] getContents() {
                    return new Object[][] {{"duration", help}};
                }
            });
            return command;
        }
    }

    private final DurationRule durationRule;

    @Spec(Spec.Target.MIXEE)
    private CommandSpec spec;

    @Option(names = "--duration", paramLabel = "SECONDS",
            description = "Length of each run in seconds (default: the scenario's, see above).")
    private Double durationS;

    @Option(names = "--period-ms", paramLabel = "MS", defaultValue = "15",
            description = "Control period in milliseconds: the controller's Tick period (default: ${DEFAULT-VALUE},"
                    + " the paper's).")
    private long periodMs;

    @Option(names = "--baud", paramLabel = "BITS_PER_S", defaultValue = "115200",
            description = "Serial line rate to the simulated DSP board (default: ${DEFAULT-VALUE}, the paper's);"
                    + " the board's cycle and the proxy's reply timeout scale with it. A 1 ms loop needs 921600.")
    private int baudRate;

    @Option(names = "--out", paramLabel = "DIR",
            description = "Directory for the CSV, plots and table (default: target/scenarios/<scenario>).")
    private Path out;

    /** Options for a scenario whose {@code --duration} follows {@code durationRule}. */
    public ScenarioOptions(DurationRule durationRule) {
        this.durationRule = durationRule;
    }

    /** The run length in nanoseconds, the rule's default when not given; too short or too long is a usage error. */
    public long durationNs() {
        double lengthS = durationS == null ? durationRule.defaultS() : durationS;
        if (!(lengthS >= durationRule.minS())) {
            throw new ParameterException(spec.commandLine(), "--duration " + seconds(lengthS) + ": must be at least "
                    + seconds(durationRule.minS()) + " s for " + article(spec.name()) + " run"
                    + (durationRule.minReason().isEmpty() ? "" : " (" + durationRule.minReason() + ")"));
        }
        if (!(lengthS <= MAX_DURATION_S)) {
            throw new ParameterException(spec.commandLine(), "--duration " + seconds(lengthS) + ": must be at most "
                    + seconds(MAX_DURATION_S) + " s (an hour)");
        }
        return Math.round(lengthS * 1e9);
    }

    /** The control period in nanoseconds; a bad value is a usage error. */
    public long periodNs() {
        if (periodMs < 1 || periodMs > 1_000) {
            throw new ParameterException(spec.commandLine(), "--period-ms=" + periodMs
                    + " is out of range: give the control period in milliseconds, from 1 to 1000 (the paper: 15)");
        }
        return TimeUnit.MILLISECONDS.toNanos(periodMs);
    }

    /** The serial line rate; a bad value is a usage error. */
    public int baudRate() {
        try {
            PlantWiring.requireBaudRate(baudRate);
        } catch (IllegalArgumentException e) {
            throw new ParameterException(spec.commandLine(), "--baud=" + baudRate + " is out of range: give bits per"
                    + " second from " + PlantWiring.MIN_BAUD_RATE + " to " + PlantWiring.MAX_BAUD_RATE + " (the paper: "
                    + PlantWiring.DEFAULT_BAUD_RATE + "; 921600 for a 1 ms loop)");
        }
        return baudRate;
    }

    /**
     * The output directory, {@code target/scenarios/<scenario>} when not given; one that cannot
     * take the results (a file, a path through a file, not writable) is a usage error, before
     * anything runs.
     */
    public Path out(String scenario) {
        Path dir = out != null ? out : Path.of("target", "scenarios", scenario);
        OutputDirectory.requireUsable(spec.commandLine(), "--out", dir);
        return dir;
    }

    /** Seconds as a user types them: {@code 2}, {@code 2.5}. */
    private static String seconds(double value) {
        return Double.isFinite(value) ? BigDecimal.valueOf(value).stripTrailingZeros().toPlainString()
                : Double.toString(value);
    }

    private static String article(String word) {
        return ("aeiou".indexOf(Character.toLowerCase(word.charAt(0))) >= 0 ? "an " : "a ") + word;
    }
}
