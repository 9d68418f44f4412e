package io.etherware.examples.scenario;

import io.etherware.examples.EtherwareDemo;
import java.io.BufferedReader;
import java.io.IOException;
import java.io.InputStreamReader;
import java.io.OutputStream;
import java.net.InetSocketAddress;
import java.nio.charset.StandardCharsets;
import java.nio.file.Path;
import java.util.ArrayList;
import java.util.List;
import java.util.concurrent.CompletableFuture;
import java.util.concurrent.ExecutionException;
import java.util.concurrent.TimeUnit;
import java.util.concurrent.TimeoutException;
import org.slf4j.Logger;
import org.slf4j.LoggerFactory;

/**
 * A scenario's second node in a JVM of its own: a hidden {@code etherware-demo} subcommand started
 * on this JVM's class path, which prints {@link #READY} on standard output once it can take part,
 * takes commands as lines on its standard input, and ends when its input closes. Its standard error
 * goes to a log file; what it prints after {@code READY} is kept, for the scenario to read its
 * results from once it stopped.
 *
 * <p>The node's JVM runs with this JVM's collector and heap options ({@link #MEMORY_OPTIONS}), so
 * both nodes of a run collect garbage alike, and with this JVM's {@code -Xlog} options that write
 * to a file named per process ({@code %p}), so a test run has the safepoint log of every JVM.
 *
 * <p>Both JVMs run on one host and share its {@code CLOCK_MONOTONIC}, so times passed between them
 * (an origin, an event's time) need no translation. Used by one scenario thread; the process's
 * output is read by a thread of its own.
 */
public final class NodeProcess implements AutoCloseable {

    /** What the node prints when it is ready. */
    public static final String READY = "READY";

    private static final Logger LOG = LoggerFactory.getLogger(NodeProcess.class);
    private static final long STOP_TIMEOUT_S = 30;
    /** The prefixes of this JVM's options that the node's JVM gets too: collector, heap, metaspace. */
    static final List<String> MEMORY_OPTIONS = List.of("-XX:+Use", "-XX:-Use", "-Xms", "-Xmx", "-Xmn",
            "-XX:+AlwaysPreTouch", "-XX:MaxGCPauseMillis=", "-XX:SoftMaxHeapSize=", "-XX:MetaspaceSize=");

    private final Process process;
    private final Path log;
    private final List<String> afterReady = new ArrayList<>();
    private final CompletableFuture<Void> outputEnded = new CompletableFuture<>();

    /**
     * Those of {@code jvmOptions} that name the collector or size the heap or metaspace, and the {@code -Xlog}
     * options whose file is named per process (others would have two JVMs write one file).
     */
    static List<String> nodeJvmOptions(List<String> jvmOptions) {
        var chosen = new ArrayList<String>();
        for (String option : jvmOptions) {
            if (MEMORY_OPTIONS.stream().anyMatch(option::startsWith)
                    || option.startsWith("-Xlog:") && option.contains("file=") && option.contains("%p")) {
                chosen.add(option);
            }
        }
        return chosen;
    }

    private NodeProcess(Process process, Path log) {
        this.process = process;
        this.log = log;
    }

    /**
     * Starts {@code etherware-demo <arguments>} in a new JVM on this JVM's class path, its standard
     * error into {@code log}, and waits up to {@code readyTimeoutS} for {@link #READY}. Standard
     * output is read to its end by a thread of its own (not by the common pool, which a busy JVM
     * may not have free), so the node never blocks on a full pipe.
     *
     * @throws IOException if the JVM does not start or does not report READY in time (its threads
     *     are then dumped into {@code log} and it is ended)
     */
    public static NodeProcess start(List<String> arguments, Path log, long readyTimeoutS) throws IOException {
        String classPath = System.getProperty("surefire.test.class.path", System.getProperty("java.class.path"));
        List<String> command = new ArrayList<>(List.of(Path.of(System.getProperty("java.home"), "bin", "java")
                .toString(), "--enable-native-access=ALL-UNNAMED"));
        command.addAll(nodeJvmOptions(java.lang.management.ManagementFactory.getRuntimeMXBean().getInputArguments()));
        command.addAll(List.of("-cp", classPath, EtherwareDemo.class.getName()));
        command.addAll(arguments);
        Process process = new ProcessBuilder(command).redirectError(log.toFile()).start();
        var node = new NodeProcess(process, log);
        var ready = new CompletableFuture<Boolean>();
        var beforeReady = new StringBuilder();
        Thread.ofPlatform().name("node-" + process.pid() + "-stdout").daemon().start(() -> {
            try (var out = new BufferedReader(new InputStreamReader(process.getInputStream(), StandardCharsets.UTF_8))) {
                for (String line = out.readLine(); line != null; line = out.readLine()) {
                    if (!ready.isDone() && line.equals(READY)) {
                        ready.complete(true);
                    } else if (ready.isDone()) {
                        synchronized (node.afterReady) {
                            node.afterReady.add(line);
                        }
                    } else {
                        synchronized (beforeReady) {
                            beforeReady.append(line).append('\n');
                        }
                    }
                }
            } catch (IOException e) {
                // the process is gone; the waits report it
            } finally {
                ready.complete(false);
                node.outputEnded.complete(null);
            }
        });
        try {
            if (ready.get(readyTimeoutS, TimeUnit.SECONDS)) {
                return node;
            }
        } catch (ExecutionException | TimeoutException e) {
            // reported below
        } catch (InterruptedException e) {
            Thread.currentThread().interrupt();
        }
        boolean alive = process.isAlive();
        if (alive) {
            dumpThreads(process.pid(), log);
            dumpThreads(ProcessHandle.current().pid(), log);
        }
        process.destroyForcibly();
        String output;
        synchronized (beforeReady) {
            output = beforeReady.toString().strip();
        }
        throw new IOException("the node's JVM did not report READY within " + readyTimeoutS + " s ("
                + (alive ? "still running" : "exited with " + process.exitValue()) + "); its standard output: '"
                + output + "'; its log: " + log);
    }

    /** The node's process id. */
    public long pid() {
        return process.pid();
    }

    /** Where its standard error goes. */
    public Path log() {
        return log;
    }

    /** Sends {@code line} to the node's standard input. */
    public void send(String line) throws IOException {
        OutputStream in = process.getOutputStream();
        in.write((line + "\n").getBytes(StandardCharsets.UTF_8));
        in.flush();
    }

    /**
     * Closes the node's input, which ends it, and waits for it (forcibly after 30 s); returns the
     * lines it printed after {@link #READY}. Idempotent.
     */
    public List<String> stop() throws InterruptedException {
        try {
            process.getOutputStream().close();
        } catch (IOException e) {
            // already gone
        }
        if (!process.waitFor(STOP_TIMEOUT_S, TimeUnit.SECONDS)) {
            LOG.warn("node (pid {}) did not stop within {} s of its input closing; ending it", process.pid(),
                    STOP_TIMEOUT_S);
            process.destroyForcibly();
            process.waitFor(STOP_TIMEOUT_S, TimeUnit.SECONDS);
        }
        try {
            outputEnded.get(STOP_TIMEOUT_S, TimeUnit.SECONDS);
        } catch (ExecutionException | TimeoutException e) {
            LOG.warn("the output of node (pid {}) did not end: {}", process.pid(), e.toString());
        }
        synchronized (afterReady) {
            return List.copyOf(afterReady);
        }
    }

    /**
     * Asks the node to end as {@code kill -TERM} does ({@link Process#destroy()}), for a node that
     * runs until SIGTERM (the deployment launcher), and waits for it (forcibly after 30 s); returns
     * the lines it printed after {@link #READY}.
     */
    public List<String> terminate() throws InterruptedException {
        process.destroy();
        return stop();
    }

    /** The lines the node printed after {@link #READY} so far. */
    public List<String> linesSoFar() {
        synchronized (afterReady) {
            return List.copyOf(afterReady);
        }
    }

    /**
     * The node's exit status, once it ended ({@link #stop}, {@link #terminate}).
     *
     * @throws IllegalThreadStateException if it still runs
     */
    public int exitValue() {
        return process.exitValue();
    }

    /** {@link #stop()}, its output dropped. */
    @Override
    public void close() throws InterruptedException {
        stop();
    }

    /**
     * {@code HOST:PORT} as an address.
     *
     * @throws IllegalArgumentException with the text and why, if it is not one
     */
    public static InetSocketAddress address(String text) {
        int colon = text.lastIndexOf(':');
        try {
            if (colon <= 0) {
                throw new NumberFormatException("no port");
            }
            return new InetSocketAddress(text.substring(0, colon), Integer.parseInt(text.substring(colon + 1)));
        } catch (IllegalArgumentException e) {
            throw new IllegalArgumentException("'" + text + "' is not HOST:PORT (" + e.getMessage() + ")", e);
        }
    }

    /** {@code address} as {@code HOST:PORT}, for {@link #address(String)} on the other side. */
    public static String hostPort(InetSocketAddress address) {
        return address.getHostString() + ":" + address.getPort();
    }

    /**
     * Appends a thread dump of process {@code pid} to {@code log} ({@code jcmd <pid> Thread.print}),
     * for a node that did not come up: which threads ran, which waited. Best effort.
     */
    private static void dumpThreads(long pid, Path log) {
        Path jcmd = Path.of(System.getProperty("java.home"), "bin", "jcmd");
        try {
            Process dump = new ProcessBuilder(jcmd.toString(), Long.toString(pid), "Thread.print")
                    .redirectErrorStream(true).redirectOutput(ProcessBuilder.Redirect.appendTo(log.toFile())).start();
            if (!dump.waitFor(20, TimeUnit.SECONDS)) {
                dump.destroyForcibly();
            }
        } catch (IOException e) {
            LOG.warn("could not dump the threads of process {}: {}", pid, e.toString());
        } catch (InterruptedException e) {
            Thread.currentThread().interrupt();
        }
    }
}
