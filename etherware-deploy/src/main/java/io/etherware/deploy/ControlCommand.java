package io.etherware.deploy;

import io.etherware.core.component.RequestFailedException;
import io.etherware.core.message.Profile;
import io.etherware.deploy.ControlSession.ControlException;
import io.etherware.services.management.Implementation;
import io.etherware.services.management.Management;
import io.etherware.services.management.ManagementException;
import io.etherware.services.management.MigrationResult;
import io.etherware.services.management.UpgradeResult;
import io.etherware.services.network.ConnectionFactory;
import io.etherware.services.status.NodeStatus;
import io.etherware.services.status.Status;
import java.io.IOException;
import java.io.PrintWriter;
import java.net.InetSocketAddress;
import java.nio.file.Path;
import java.time.Duration;
import java.util.concurrent.Callable;
import java.util.concurrent.CompletableFuture;
import java.util.concurrent.ExecutionException;
import java.util.concurrent.TimeUnit;
import java.util.concurrent.TimeoutException;
import picocli.CommandLine.Command;
import picocli.CommandLine.Model.CommandSpec;
import picocli.CommandLine.Option;
import picocli.CommandLine.ParameterException;
import picocli.CommandLine.ParentCommand;
import picocli.CommandLine.Spec;

/**
 * {@code control --node HOST:PORT status|upgrade|migrate}: connects to a running node as a peer
 * does ({@link ControlSession}) and asks its status service or its management service, printing
 * the answer as text, or as JSON with {@code --json}. Exit status 0 for an answer that reports
 * success, 1 for a refusal, a failure or no answer (the message says which and why), 2 for a usage
 * error.
 *
 * <p>What a node tells: {@code status} lists the node and its peers (connection, clock offset), its
 * components (profile, state, counters, deadline misses) and its dispatchers (start latency
 * percentiles, misses). An upgrade or a migration is served only if the node's
 * {@code <management>} lets this tool's node id ({@code --id}) ask for it.
 *
 * <p>Run by picocli on the main thread.
 */
@Command(name = "control", mixinStandardHelpOptions = true, sortOptions = false,
        header = "Ask a running node for its status, or for an upgrade or a migration.",
        subcommands = {ControlCommand.StatusCommand.class, ControlCommand.UpgradeCommand.class,
            ControlCommand.MigrateCommand.class},
        footer = {"", "Examples:", "  control --node 127.0.0.1:7401 status",
            "  control --node 127.0.0.1:7401 --json status",
            "  control --node 127.0.0.1:7401 --id ops migrate --component controller --to node1"})
public final class ControlCommand implements Runnable {

    /** Exit status of a refusal, a failure or no answer. */
    public static final int FAILED = 1;

    @Spec
    private CommandSpec spec;

    @Option(names = "--node", required = true, paramLabel = "HOST:PORT", description = "The node to ask: where its"
            + " network listens.")
    private String node;

    /** The id when neither {@code --id} nor a TLS certificate names one. */
    public static final String DEFAULT_ID = "control";

    @Option(names = "--id", paramLabel = "NAME", description = "This tool's node id, which the node's access list"
            + " names (default: with TLS, its certificate's CN, otherwise " + DEFAULT_ID + ").")
    private String id;

    @Option(names = "--json", description = "Print the answer as JSON.")
    private boolean json;

    @Option(names = "--timeout", paramLabel = "DURATION", defaultValue = "5s", description = "How long to wait for"
            + " the connection and for each answer, e.g. 500ms, 10s (default: ${DEFAULT-VALUE}).")
    private String timeout;

    @Option(names = "--lanes", paramLabel = "N", defaultValue = "2", description = "Connections per pair of nodes,"
            + " as the node's network has them (default: ${DEFAULT-VALUE}).")
    private int lanes;

    @Option(names = "--key-store", paramLabel = "FILE", description = "This tool's PKCS#12 key store, for a node"
            + " whose network uses TLS (with the three options below).")
    private Path keyStore;

    @Option(names = "--key-store-password-file", paramLabel = "FILE")
    private Path keyStorePasswordFile;

    @Option(names = "--trust-store", paramLabel = "FILE", description = "The deployment CA's PKCS#12 trust store.")
    private Path trustStore;

    @Option(names = "--trust-store-password-file", paramLabel = "FILE")
    private Path trustStorePasswordFile;

    @Option(names = "--insecure", description = "Dial a node beyond loopback over plain TCP, on a network you trust.")
    private boolean insecure;

    /** A command for picocli to fill in. */
    public ControlCommand() {
    }

    /**
     * Runs the control tool as a program of its own.
     *
     * @param args the command line
     */
    public static void main(String[] args) {
        System.exit(new picocli.CommandLine(new ControlCommand()).execute(args));
    }

    @Override
    public void run() {
        throw new ParameterException(spec.commandLine(), "Name what to ask: status, upgrade or migrate");
    }

    /** Connects, runs {@code ask} in the session, prints its answer; the exit status. */
    private int ask(CommandSpec command, Request request) {
        PrintWriter out = command.commandLine().getOut();
        PrintWriter err = command.commandLine().getErr();
        Duration wait;
        InetSocketAddress address;
        ConnectionFactory factory;
        String as;
        try {
            wait = Durations.parse(timeout);
            address = address(node);
            factory = connectionFactory();
            if (lanes < 1 || lanes > 2) {
                throw new IllegalArgumentException("--lanes=" + lanes + ": must be 1 or 2, as the node's network has");
            }
            as = nodeId(factory);
        } catch (IllegalArgumentException | IOException e) {
            throw new ParameterException(command.commandLine(), e.getMessage());
        }
        try (ControlSession session = ControlSession.open(as, address, factory, lanes, insecure, wait)) {
            Answer answer = request.ask(session, wait);
            out.println(json ? answer.json() : answer.text());
            out.flush();
            return answer.success() ? 0 : FAILED;
        } catch (ControlException e) {
            err.println("control: " + e.getMessage());
            err.flush();
            return FAILED;
        }
    }

    /** The tool's node id: {@code --id}, else the certificate's CN with TLS, else {@value #DEFAULT_ID}. */
    private String nodeId(ConnectionFactory factory) {
        String named = factory.localNodeId().orElse(null);
        if (id != null && named != null && !id.equals(named)) {
            throw new IllegalArgumentException("--id=" + id + ", but the key store's certificate names '" + named
                    + "': with TLS the id is the certificate's CN; drop --id or use that node's key store");
        }
        String chosen = id != null ? id : named != null ? named : DEFAULT_ID;
        if (!Profile.isName(chosen)) {
            throw new IllegalArgumentException("--id=" + chosen + ": use letters, digits, '_', '.' and '-'");
        }
        return chosen;
    }

    private ConnectionFactory connectionFactory() throws IOException {
        boolean any = keyStore != null || keyStorePasswordFile != null || trustStore != null
                || trustStorePasswordFile != null;
        if (!any) {
            return ConnectionFactory.plain();
        }
        if (keyStore == null || keyStorePasswordFile == null || trustStore == null || trustStorePasswordFile == null) {
            throw new IllegalArgumentException("TLS needs all four: --key-store, --key-store-password-file,"
                    + " --trust-store, --trust-store-password-file");
        }
        char[] keyPassword = NetworkSections.readPassword(keyStorePasswordFile);
        char[] trustPassword = NetworkSections.readPassword(trustStorePasswordFile);
        try {
            return ConnectionFactory.tls(keyStore, keyPassword, trustStore, trustPassword);
        } finally {
            java.util.Arrays.fill(keyPassword, '\0');
            java.util.Arrays.fill(trustPassword, '\0');
        }
    }

    private static InetSocketAddress address(String text) {
        try {
            return HostPort.parse(text);
        } catch (IllegalArgumentException e) {
            throw new IllegalArgumentException("--node=" + text + ": " + e.getMessage(), e);
        }
    }

    /** Waits for {@code future}, turning its failures into the tool's. */
    private static <T> T await(CompletableFuture<T> future, Duration wait, String what) throws ControlException {
        try {
            return future.get(wait.toMillis() + 1_000, TimeUnit.MILLISECONDS);
        } catch (ExecutionException e) {
            if (e.getCause() instanceof RequestFailedException failed) {
                throw new ControlException(what + " got no answer: " + failed.getMessage(), failed);
            }
            throw new ControlException(what + " failed: " + e.getCause(), e.getCause());
        } catch (TimeoutException e) {
            throw new ControlException(what + " got no answer within " + wait.toMillis() + " ms", e);
        } catch (InterruptedException e) {
            Thread.currentThread().interrupt();
            throw new ControlException(what + " was interrupted", e);
        }
    }

    /** One kind of request. */
    @FunctionalInterface
    private interface Request {
        Answer ask(ControlSession session, Duration wait) throws ControlException;
    }

    /** What the node answered, in both forms. */
    private record Answer(boolean success, String text, String json) {
    }

    /** {@code control status}. */
    @Command(name = "status", mixinStandardHelpOptions = true,
            description = "The node and its peers, its components and its dispatchers.")
    static final class StatusCommand implements Callable<Integer> {

        @ParentCommand
        private ControlCommand parent;

        @Spec
        private CommandSpec spec;

        @Override
        public Integer call() {
            return parent.ask(spec, (session, wait) -> {
                NodeStatus status = await(Status.request(session.node(), session.targetId(), wait), wait,
                        "the status request");
                return new Answer(true, StatusText.format(status), StatusJson.format(status));
            });
        }
    }

    /** {@code control upgrade}. */
    @Command(name = "upgrade", mixinStandardHelpOptions = true,
            description = "Replace a component's logic with another class, from the node's class path or a signed"
                    + " plugin jar in a directory its <management> allows.")
    static final class UpgradeCommand implements Callable<Integer> {

        @ParentCommand
        private ControlCommand parent;

        @Spec
        private CommandSpec spec;

        @Option(names = "--component", required = true, paramLabel = "PROFILE",
                description = "The component: its profile or a query for it, e.g. controller[pendulum=1].")
        private String component;

        @Option(names = "--class", required = true, paramLabel = "NAME", description = "The new logic's class.")
        private String className;

        @Option(names = "--jar", paramLabel = "PATH", description = "The plugin jar on the node's file system.")
        private Path jar;

        @Override
        public Integer call() {
            Profile target = profile(spec, component);
            Implementation implementation = jar != null ? Implementation.fromJar(jar, className)
                    : Implementation.ofClass(className);
            return parent.ask(spec, (session, wait) -> {
                session.requireManagement(wait);
                try {
                    UpgradeResult result = await(Management.upgrade(session.node(), session.targetId(), target,
                            implementation, wait), wait, "the upgrade request");
                    return new Answer(true, StatusText.format(session.targetId(), result),
                            StatusJson.format(session.targetId(), result));
                } catch (ControlException e) {
                    return refusal(e);
                }
            });
        }
    }

    /** {@code control migrate}. */
    @Command(name = "migrate", mixinStandardHelpOptions = true,
            description = "Move a component from the node to another node, with its state and its messages.")
    static final class MigrateCommand implements Callable<Integer> {

        @ParentCommand
        private ControlCommand parent;

        @Spec
        private CommandSpec spec;

        @Option(names = "--component", required = true, paramLabel = "PROFILE",
                description = "The component: its profile or a query for it.")
        private String component;

        @Option(names = "--to", required = true, paramLabel = "NODE", description = "The node to move it to.")
        private String toNode;

        @Override
        public Integer call() {
            Profile target = profile(spec, component);
            return parent.ask(spec, (session, wait) -> {
                session.requireManagement(wait);
                try {
                    MigrationResult result = await(Management.migrate(session.node(), session.targetId(), target,
                            toNode, wait), wait, "the migration request");
                    return new Answer(true, StatusText.format(result), StatusJson.format(result));
                } catch (ControlException e) {
                    return refusal(e);
                }
            });
        }
    }

    /** A management answer that refused or failed: printed like an answer, with exit status 1. */
    private static Answer refusal(ControlException e) throws ControlException {
        if (e.getCause() instanceof ManagementException refused) {
            return new Answer(false, StatusText.format(refused.failure()), StatusJson.format(refused.failure()));
        }
        throw e;
    }

    private static Profile profile(CommandSpec spec, String text) {
        try {
            return Profile.parse(text);
        } catch (IllegalArgumentException e) {
            throw new ParameterException(spec.commandLine(), "--component: " + e.getMessage());
        }
    }
}
