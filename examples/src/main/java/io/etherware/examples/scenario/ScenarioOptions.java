package io.etherware.examples.scenario;

import java.nio.file.Path;
import java.util.concurrent.TimeUnit;
import picocli.CommandLine.Model.CommandSpec;
import picocli.CommandLine.Option;
import picocli.CommandLine.ParameterException;
import picocli.CommandLine.Spec;

/**
 * The options every scenario takes ({@code --duration}, {@code --period-ms}, {@code --baud}, {@code --out}), as a
 * picocli mixin. Each scenario supplies its own default duration.
 *
 * <p>Filled in by picocli on the command's thread; not thread-safe.
 */
public final class ScenarioOptions {

    /** Longest run accepted, seconds. */
    public static final double MAX_DURATION_S = 3_600.0;

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

    /** The run length in nanoseconds, {@code defaultS} when not given; a bad value is a usage error. */
    public long durationNs(double defaultS) {
        double seconds = durationS == null ? defaultS : durationS;
        if (!(seconds >= 1.0 && seconds <= MAX_DURATION_S)) {
            throw new ParameterException(spec.commandLine(), "--duration=" + durationS
                    + " is out of range: give the seconds of each run, from 1 to " + (long) MAX_DURATION_S);
        }
        return Math.round(seconds * 1e9);
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

    /** The output directory, {@code target/scenarios/<scenario>} when not given. */
    public Path out(String scenario) {
        return out != null ? out : Path.of("target", "scenarios", scenario);
    }
}
