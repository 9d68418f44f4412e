package io.etherware.examples.migrate;

import io.etherware.core.kernel.DeliveryWarmUp;
import io.etherware.core.kernel.EtherwareNode;
import io.etherware.core.message.Profile;
import io.etherware.examples.scenario.ControlListeners;
import io.etherware.examples.scenario.NodeProcess;
import io.etherware.examples.scenario.Requester;
import io.etherware.examples.scenario.Schedulers;
import io.etherware.pendulum.components.DspProxy;
import io.etherware.pendulum.components.PendulumController;
import io.etherware.services.management.AccessRule;
import io.etherware.services.management.Management;
import io.etherware.services.management.ManagementConfig;
import io.etherware.services.management.ManagementService;
import io.etherware.services.network.NetworkConfig;
import io.etherware.services.network.NetworkMessenger;
import java.io.IOException;
import java.io.InputStream;
import java.io.PrintWriter;
import java.net.InetSocketAddress;
import java.nio.file.Files;
import java.nio.file.NoSuchFileException;
import java.nio.file.Path;
import java.security.cert.CertificateException;
import java.security.cert.CertificateFactory;
import java.security.cert.X509Certificate;
import java.time.Duration;
import java.util.List;
import java.util.Set;
import java.util.concurrent.Callable;
import picocli.CommandLine.Command;
import picocli.CommandLine.Model.CommandSpec;
import picocli.CommandLine.Option;
import picocli.CommandLine.ParameterException;
import picocli.CommandLine.Spec;

/**
 * {@code etherware-demo control-node}: node 2 of the migrate scenario and of {@code upgrade
 * --remote}, in a JVM of its own, which {@link MigrateScenario} or
 * {@link io.etherware.examples.upgrade.UpgradeScenario} starts. It dials the plant's node, hosts the controller
 * ({@link ListenedController}) on Etherware-RT, reports each cycle to the scenario's recorder on
 * the plant's node ({@link CycleReport}), and serves management requests from other nodes (the
 * migration request, from the plant node's {@link Requester}, and its steps; with {@code --plugins}
 * and {@code --trust}, also the upgrade request, for a plugin jar in that directory signed by that
 * certificate's key). An idle spare controller, {@link WarmUp#REHEARSAL}, is there
 * for the scenario to migrate once before the pendulum starts. Prints {@code READY} on standard output once the DSPProxy,
 * the recorder and the plant's management service resolve from here, and runs until its standard
 * input closes.
 *
 * <p>Run by picocli on the main thread, which then only waits.
 */
@Command(name = "control-node", hidden = true, mixinStandardHelpOptions = true,
        description = "Node 2 of the migrate and remote upgrade scenarios, started by them in a second JVM.")
public final class ControlNodeCommand implements Callable<Integer> {

    /** What the node prints when it is ready for the board to start. */
    public static final String READY = NodeProcess.READY;
    private static final Duration RESOLVE_TIMEOUT = Duration.ofSeconds(30);

    @Spec
    private CommandSpec spec;

    @Option(names = "--connect", required = true, paramLabel = "HOST:PORT",
            description = "The plant's node (node 1) to dial.")
    private String connect;

    @Option(names = "--listener", required = true, paramLabel = "NAME",
            description = "The control listener name the controller's configuration carries.")
    private String listener;

    @Option(names = "--plugins", paramLabel = "DIR",
            description = "Let the plant's node upgrade the controller from a signed plugin jar in this directory"
                    + " (with --trust).")
    private Path plugins;

    @Option(names = "--trust", paramLabel = "CERT",
            description = "The certificate (PEM or DER) whose key signs the plugin jars (with --plugins).")
    private Path trust;

    @Override
    public Integer call() throws Exception {
        ManagementConfig management = management();
        InetSocketAddress plant = address(connect);
        spec.commandLine().getErr().println("control-node: " + MigrateConfig.CONTROL_NODE + " starting, dialing " + plant);
        spec.commandLine().getErr().flush();
        PrintWriter out = spec.commandLine().getOut();
        try (var node = EtherwareNode.builder().nodeId(MigrateConfig.CONTROL_NODE)
                .scheduler(Schedulers::etherwareRt).build().start();
                var net = NetworkMessenger.start(node, NetworkConfig.builder().codec(WarmUp.warmedCodec(node))
                        .listen(new InetSocketAddress("127.0.0.1", 0)).peer(plant).build());
                ControlListeners.Registration registration = ControlListeners.register(listener,
                        CycleReport.forwarder(node))) {
            DeliveryWarmUp.run(node);
            // Node 1 asks this node to move the controller to it.
            ManagementService.install(node, management, net);
            node.add(PendulumController.DEFAULT_PROFILE,
                    () -> new ListenedController(ListenedController.configuration(listener)));
            // An idle spare that the scenario migrates once before the pendulum starts (WarmUp.REHEARSAL).
            node.add(WarmUp.REHEARSAL, () -> new ListenedController(ListenedController.configuration(listener)));
            // A migration's steps go to the plant node's management service; an upgrade needs none there.
            List<Profile> needed = plugins != null
                    ? List.of(DspProxy.DEFAULT_PROFILE, CycleReport.RECORDER, Requester.PROFILE)
                    : List.of(DspProxy.DEFAULT_PROFILE, CycleReport.RECORDER, Requester.PROFILE,
                            Management.profileOf(MigrateConfig.PLANT_NODE));
            for (var profile : needed) {
                if (!net.awaitResolvable(profile, RESOLVE_TIMEOUT)) {
                    spec.commandLine().getErr().println("control-node: " + profile + " does not resolve from "
                            + node.nodeId() + " within " + RESOLVE_TIMEOUT.toSeconds() + " s");
                    return 1;
                }
            }
            out.println(READY);
            out.flush();
            while (System.in.read() >= 0) {
                // runs until the scenario closes our input (or ends the process)
            }
        }
        return 0;
    }

    /**
     * The plant's node may migrate the controllers; with {@code --plugins} and {@code --trust},
     * also upgrade them from that directory's jars signed by that key.
     */
    private ManagementConfig management() throws IOException {
        if ((plugins == null) != (trust == null)) {
            throw new ParameterException(spec.commandLine(), "--plugins and --trust go together: give both, or"
                    + " neither (no upgrades from other nodes)");
        }
        ManagementConfig.Builder builder = MigrateConfig.managementBuilder(MigrateConfig.PLANT_NODE);
        if (plugins == null) {
            return builder.build();
        }
        X509Certificate certificate;
        try (InputStream in = Files.newInputStream(trust)) {
            certificate = (X509Certificate) CertificateFactory.getInstance("X.509").generateCertificate(in);
        } catch (CertificateException | NoSuchFileException e) {
            throw new ParameterException(spec.commandLine(), "--trust=" + trust + " is not a readable X.509"
                    + " certificate: " + e.getMessage());
        }
        try {
            builder.allowDirectory(plugins);
        } catch (IllegalArgumentException e) {
            throw new ParameterException(spec.commandLine(), "--plugins=" + plugins + ": " + e.getMessage());
        }
        return builder.trustedSigner(certificate)
                .allowRemote(MigrateConfig.PLANT_NODE, Set.of(AccessRule.Operation.UPGRADE), "controller").build();
    }

    private InetSocketAddress address(String text) {
        try {
            return NodeProcess.address(text);
        } catch (IllegalArgumentException e) {
            throw new ParameterException(spec.commandLine(), "--connect=" + e.getMessage());
        }
    }
}
