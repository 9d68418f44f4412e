package io.etherware.deploy;

import java.io.PrintWriter;
import java.net.InetSocketAddress;
import java.nio.charset.StandardCharsets;
import java.nio.file.Files;
import java.nio.file.Path;
import java.util.LinkedHashMap;
import java.util.Map;
import java.util.concurrent.Callable;
import java.util.concurrent.atomic.AtomicBoolean;
import picocli.CommandLine;
import picocli.CommandLine.Command;
import picocli.CommandLine.Model.CommandSpec;
import picocli.CommandLine.Option;
import picocli.CommandLine.Parameters;
import picocli.CommandLine.Spec;

/**
 * {@code node FILE}: starts the node a deployment file describes and runs it until the process
 * is asked to end (SIGTERM, SIGINT), then closes it in order ({@link DeployedNode#close}). A bad
 * file is reported on standard error, naming the line, element and fix, and nothing starts (exit
 * status 2). Prints {@code READY} on standard output once the node runs (after a line saying
 * where it listens, and one with its view's address if it has a {@code <view>}), for scripts and
 * process supervisors that wait for it.
 *
 * <p>Run by picocli on the main thread, which then waits for the node to close.
 */
@Command(name = "node", mixinStandardHelpOptions = true, sortOptions = false,
        header = "Start a node from its deployment file and run it until SIGTERM.",
        description = {"The file is checked against etherware-deployment.xsd and the rules in DEPLOYMENT.md before"
                + " anything starts. ${name} and ${name:-default} in attribute values take the values of -P."},
        footer = {"", "Example: node -P listen=127.0.0.1:7400 deploy/pendulum-node1.xml"})
public final class Launcher implements Callable<Integer> {

    /** What the launcher prints once the node runs. */
    public static final String READY = "READY";
    /** Exit status for a deployment that cannot start. */
    public static final int BAD_DEPLOYMENT = 2;

    @Spec
    private CommandSpec spec;

    @Parameters(index = "0", paramLabel = "FILE", description = "The node's deployment file.")
    private Path file;

    @Option(names = "-P", paramLabel = "NAME=VALUE", mapFallbackValue = "",
            description = "A value for ${NAME} in the file; repeatable.")
    private Map<String, String> properties = new LinkedHashMap<>();

    @Option(names = "--check", description = "Only read and check the file (the components' factories are not"
            + " run, so their settings are checked at start), print a summary and exit.")
    private boolean check;

    @Option(names = "--address-file", paramLabel = "PATH",
            description = "Write the address the network listens on (HOST:PORT) to this file before READY.")
    private Path addressFile;

    /** A launcher for picocli to fill in. */
    public Launcher() {
    }

    /**
     * Runs the launcher as a program of its own.
     *
     * @param args the command line
     */
    public static void main(String[] args) {
        System.exit(new CommandLine(new Launcher()).execute(args));
    }

    @Override
    public Integer call() throws Exception {
        PrintWriter out = spec.commandLine().getOut();
        PrintWriter err = spec.commandLine().getErr();
        Deployment deployment;
        DeployedNode deployed;
        try {
            deployment = new DeploymentReader().read(file, properties);
            if (check) {
                out.println("OK " + file + ": node " + deployment.nodeId() + ", scheduler "
                        + deployment.scheduler().description() + ", " + deployment.components().size()
                        + " component(s)" + deployment.network().map(n -> ", listening on "
                        + HostPort.format(n.listenAddress()) + ", " + n.peers().size() + " peer(s)").orElse(", no network")
                        + deployment.view().map(v -> ", view on " + HostPort.format(v.config().listen())).orElse(""));
                out.flush();
                return 0;
            }
            deployed = DeployedNode.start(deployment);
        } catch (DeploymentException e) {
            err.println("node: " + e.getMessage());
            err.flush();
            return BAD_DEPLOYMENT;
        }
        var asked = new AtomicBoolean();
        Thread hook = Thread.ofPlatform().name("node-shutdown").unstarted(() -> {
            asked.set(true);
            deployed.close();
        });
        Runtime.getRuntime().addShutdownHook(hook);
        if (addressFile != null && deployed.listenAddress().isPresent()) {
            Files.writeString(addressFile, HostPort.format(deployed.listenAddress().get()) + "\n", StandardCharsets.UTF_8);
        }
        out.println("node " + deployment.nodeId() + " running" + deployed.listenAddress()
                .map(a -> ", listening on " + HostPort.format(a)).orElse(""));
        deployed.viewUrl().ifPresent(url -> out.println("view on " + url));
        out.println(READY);
        out.flush();
        // Until the node closes: from the shutdown hook, or by itself (an escalation that stopped it).
        deployed.node().closedFuture().exceptionally(failure -> null).join();
        if (!asked.get()) {
            deployed.close(); // the node closed by itself: close the rest in order too
            err.println("node: " + deployment.nodeId() + " closed by itself; see its log");
            err.flush();
            return 1;
        }
        return 0;
    }
}
