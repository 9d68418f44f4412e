package io.etherware.examples.serial;

import io.etherware.core.time.NodeClock;
import io.etherware.examples.scenario.NodeProcess;
import io.etherware.examples.scenario.PendulumRig;
import io.etherware.examples.scenario.PlantWiring;
import io.etherware.examples.scenario.SimThreads;
import io.etherware.pendulum.dsp.DspBoard;
import io.etherware.pendulum.plant.PendulumState;
import io.etherware.pendulum.serial.JSerialCommLink;
import io.etherware.pendulum.serial.PseudoTerminalLink;
import io.etherware.rt.platform.AbsoluteSleeper;
import java.io.BufferedReader;
import java.io.IOException;
import java.io.InputStreamReader;
import java.io.PrintWriter;
import java.nio.charset.StandardCharsets;
import java.nio.file.Files;
import java.nio.file.Path;
import java.util.Locale;
import java.util.concurrent.Callable;
import java.util.concurrent.CompletableFuture;
import java.util.concurrent.TimeUnit;
import java.util.concurrent.atomic.AtomicBoolean;
import java.util.concurrent.locks.LockSupport;
import picocli.CommandLine.Command;
import picocli.CommandLine.Model.CommandSpec;
import picocli.CommandLine.Option;
import picocli.CommandLine.ParameterException;
import picocli.CommandLine.Spec;

/**
 * {@code etherware-demo dsp-board}: the simulated DSP board with its pendulum as a process of its
 * own, serving a serial port, so that a node drives it through its real serial stack
 * ({@link JSerialCommLink}) as it would drive the hardware. By default the port is a new
 * pseudo-terminal, whose device path it prints ({@code PORT /dev/pts/N}) and writes to
 * {@code --port-file}; {@code --port} serves a real port instead (e.g. one end of a null-modem
 * pair). The pendulum starts falling when the board starts: on the line {@code START} on standard
 * input, at once with {@code --start-now}, or when the node first sends a request with
 * {@code --start-on-request}. Prints {@code READY} when the port is open, runs
 * until its standard input closes, then prints a summary line of the plant's ground truth.
 *
 * <p>Run by picocli on the main thread.
 */
@Command(name = "dsp-board", mixinStandardHelpOptions = true, sortOptions = false,
        header = "Run the simulated DSP board and pendulum as a process, on a pseudo-terminal or a serial port.",
        description = {"The board and the plant run in real time (SCHED_FIFO " + SimThreads.BOARD_PRIORITY
                + " where granted). A node opens the printed port with jSerialComm. The pendulum starts on a START"
                + " line on standard input (or --start-now); the board stops when standard input closes."},
        footer = {"", "Example: etherware-demo dsp-board --port-file /tmp/board.port --start-now"})
public final class DspBoardCommand implements Callable<Integer> {

    /** The summary line's first word. */
    public static final String SUMMARY = "SUMMARY";
    /** How often the ground truth is sampled for the summary. */
    private static final long SAMPLE_NS = TimeUnit.MILLISECONDS.toNanos(5);

    @Spec
    private CommandSpec spec;

    @Option(names = "--port", paramLabel = "NAME",
            description = "Serve this serial port (e.g. /dev/ttyUSB0) instead of a new pseudo-terminal.")
    private String port;

    @Option(names = "--port-file", paramLabel = "PATH",
            description = "Write the device path a node should open to this file, before READY.")
    private Path portFile;

    @Option(names = "--baud", paramLabel = "BITS_PER_S", defaultValue = "115200",
            description = "Serial line rate (default: ${DEFAULT-VALUE}); the board's cycle scales with it.")
    private int baudRate;

    @Option(names = "--theta2", paramLabel = "RAD", defaultValue = "0.02",
            description = "Where the pendulum starts, off upright (default: ${DEFAULT-VALUE} rad).")
    private double theta2;

    @Option(names = "--start-now", description = "Start the board at once, not on a START line.")
    private boolean startNow;

    @Option(names = "--start-on-request", description = "Start the board when the node first sends it a request"
            + " (the pendulum is held upright until the control loop runs), not on a START line.")
    private boolean startOnRequest;

    @Override
    public Integer call() throws Exception {
        PlantWiring wiring;
        try {
            wiring = new PlantWiring(baudRate);
        } catch (IllegalArgumentException e) {
            throw new ParameterException(spec.commandLine(), "--baud: " + e.getMessage());
        }
        if (!(Math.abs(theta2) < 0.3)) {
            throw new ParameterException(spec.commandLine(), "--theta2=" + theta2 + ": must be within ±0.3 rad");
        }
        PrintWriter out = spec.commandLine().getOut();
        NodeClock clock = NodeClock.system();
        if (startNow && startOnRequest) {
            throw new ParameterException(spec.commandLine(), "--start-now and --start-on-request: choose one");
        }
        FirstRequestLink link;
        String devicePath;
        if (port != null) {
            link = new FirstRequestLink(JSerialCommLink.open(port, baudRate));
            devicePath = port;
        } else {
            PseudoTerminalLink pty = PseudoTerminalLink.open();
            link = new FirstRequestLink(pty);
            devicePath = pty.slavePath();
        }
        var threads = new SimThreads();
        try (link; DspBoard board = new DspBoard(wiring.board(), PendulumRig.PARAMETERS,
                new PendulumState(0.0, 0.0, theta2, 0.0), link)) {
            if (portFile != null) {
                Files.writeString(portFile, devicePath + "\n", StandardCharsets.UTF_8);
            }
            out.println("PORT " + devicePath);
            out.println(NodeProcess.READY);
            out.flush();
            var input = new BufferedReader(new InputStreamReader(System.in, StandardCharsets.UTF_8));
            var startLine = new CompletableFuture<Boolean>(); // true on START, false if the input closed first
            var inputClosed = new CompletableFuture<Void>();
            Thread.ofPlatform().daemon().name("dsp-board-input").start(() -> {
                try {
                    for (String line = input.readLine(); line != null; line = input.readLine()) {
                        if (line.equals("START")) {
                            startLine.complete(true);
                        }
                    }
                } catch (IOException e) {
                    // as closed
                } finally {
                    startLine.complete(false);
                    inputClosed.complete(null);
                }
            });
            boolean start = startNow
                    || (startOnRequest ? link.awaitFirstBytes(() -> !inputClosed.isDone()) : startLine.join());
            if (!start) {
                return 0; // closed before the start: nothing ran
            }
            long startNs = clock.nanoTime();
            board.startRealTime(clock, threads.fifo("dsp-board", SimThreads.BOARD_PRIORITY),
                    AbsoluteSleeper.forClock(clock));
            // Written by the sampler only, read after joining it.
            double[] maxAbsTheta2 = {Math.abs(theta2)};
            var running = new AtomicBoolean(true);
            Thread sampler = Thread.ofPlatform().daemon().name("dsp-board-sampler").start(() -> {
                while (running.get()) {
                    maxAbsTheta2[0] = Math.max(maxAbsTheta2[0], Math.abs(board.plantState().theta2Rad()));
                    LockSupport.parkNanos(SAMPLE_NS);
                }
            });
            inputClosed.join(); // runs until the input closes
            running.set(false);
            sampler.join(TimeUnit.SECONDS.toMillis(5));
            double max = maxAbsTheta2[0];
            PendulumState end = board.plantState();
            out.println(String.format(Locale.ROOT, "%s seconds=%.1f maxAbsTheta2=%.4f fell=%b finalTheta2=%.4f"
                    + " lateCycles=%d", SUMMARY, (clock.nanoTime() - startNs) / 1e9, max, max > 0.5, end.theta2Rad(),
                    board.lateCycles()));
            threads.grants().forEach(grant -> out.println("  " + grant.toLine()));
            out.flush();
        }
        return 0;
    }
}
