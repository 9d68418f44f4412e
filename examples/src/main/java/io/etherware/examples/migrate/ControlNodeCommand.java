package io.etherware.examples.migrate;

import io.etherware.core.kernel.EtherwareNode;
import io.etherware.examples.scenario.ControlListeners;
import io.etherware.examples.scenario.NodeProcess;
import io.etherware.examples.scenario.Schedulers;
import io.etherware.pendulum.components.DspProxy;
import io.etherware.pendulum.components.PendulumController;
import io.etherware.services.management.Management;
import io.etherware.services.management.ManagementService;
import io.etherware.services.network.NetworkConfig;
import io.etherware.services.network.NetworkMessenger;
import java.io.PrintWriter;
import java.net.InetSocketAddress;
import java.time.Duration;
import java.util.List;
import java.util.concurrent.Callable;
import picocli.CommandLine.Command;
import picocli.CommandLine.Model.CommandSpec;
import picocli.CommandLine.Option;
import picocli.CommandLine.ParameterException;
import picocli.CommandLine.Spec;

/**
 * {@code etherware-demo migrate-node}: the migration scenario's node 2, in a JVM of its own, which
 * {@link MigrateScenario} starts. It dials the plant's node, hosts the controller
 * ({@link ListenedController}) on Etherware-RT, reports each cycle to the scenario's recorder on
 * the plant's node ({@link CycleReport}), and serves management requests from other nodes (the
 * migration request and its steps). An idle spare controller, {@link WarmUp#REHEARSAL}, is there
 * for the scenario to migrate once before the pendulum starts. Prints {@code READY} on standard output once the DSPProxy,
 * the recorder and the plant's management service resolve from here, and runs until its standard
 * input closes.
 *
 * <p>Run by picocli on the main thread, which then only waits.
 */
@Command(name = "migrate-node", hidden = true, mixinStandardHelpOptions = true,
        description = "Node 2 of the migrate scenario, started by it in a second JVM.")
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

    @Override
    public Integer call() throws Exception {
        InetSocketAddress plant = address(connect);
        spec.commandLine().getErr().println("migrate-node: " + MigrateConfig.CONTROL_NODE + " starting, dialing " + plant);
        spec.commandLine().getErr().flush();
        PrintWriter out = spec.commandLine().getOut();
        try (var node = EtherwareNode.builder().nodeId(MigrateConfig.CONTROL_NODE)
                .scheduler(Schedulers::etherwareRt).build().start();
                var net = NetworkMessenger.start(node, NetworkConfig.builder().codec(WarmUp.warmedCodec(node))
                        .listen(new InetSocketAddress("127.0.0.1", 0)).peer(plant).build());
                ControlListeners.Registration registration = ControlListeners.register(listener,
                        CycleReport.forwarder(node))) {
            // Node 1 asks this node to move the controller to it.
            ManagementService.install(node, MigrateConfig.management(MigrateConfig.PLANT_NODE), net);
            node.add(PendulumController.DEFAULT_PROFILE,
                    () -> new ListenedController(ListenedController.configuration(listener)));
            // An idle spare that the scenario migrates once before the pendulum starts (WarmUp.REHEARSAL).
            node.add(WarmUp.REHEARSAL, () -> new ListenedController(ListenedController.configuration(listener)));
            for (var profile : List.of(DspProxy.DEFAULT_PROFILE, CycleReport.RECORDER,
                    Management.profileOf(MigrateConfig.PLANT_NODE))) {
                if (!net.awaitResolvable(profile, RESOLVE_TIMEOUT)) {
                    spec.commandLine().getErr().println("migrate-node: " + profile + " does not resolve from "
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

    private InetSocketAddress address(String text) {
        try {
            return NodeProcess.address(text);
        } catch (IllegalArgumentException e) {
            throw new ParameterException(spec.commandLine(), "--connect=" + e.getMessage());
        }
    }
}
