package io.etherware.examples.deploy;

import static org.junit.jupiter.api.Assertions.assertEquals;
import static org.junit.jupiter.api.Assertions.assertThrows;
import static org.junit.jupiter.api.Assertions.assertTrue;

import io.etherware.deploy.DeployedNode;
import io.etherware.deploy.Deployment;
import io.etherware.deploy.DeploymentException;
import io.etherware.deploy.DeploymentReader;
import io.etherware.pendulum.components.DspProxy;
import io.etherware.pendulum.components.PendulumController;
import java.nio.file.Path;
import java.util.List;
import java.util.Map;
import org.junit.jupiter.api.Test;
import org.junit.jupiter.api.io.TempDir;

/** The deployment files the project ships read as they should, and name the pendulum's profiles. */
class DeploymentFilesTest {

    private static final Path NODE1 = Path.of("deploy/pendulum-node1.xml");
    private static final Path NODE2 = Path.of("deploy/pendulum-node2.xml");
    private static final Path ONE_NODE = Path.of("deploy/pendulum-one-node.xml");

    @Test
    void shouldDescribeNodeOneAsTheBoardTheProxyAndTheNotifierTickingTheControllerOnNodeTwo() throws Exception {
        Deployment node1 = new DeploymentReader().read(NODE1);

        assertEquals("node1", node1.nodeId());
        assertEquals(List.of(DspProxy.DEFAULT_PROFILE), node1.components().stream()
                .map(Deployment.ComponentPlan::profile).toList());
        assertEquals(PendulumController.DEFAULT_PROFILE,
                node1.notifier().orElseThrow().subscriptions().getFirst().target());
        assertEquals(15_000_000L, node1.notifier().orElseThrow().subscriptions().getFirst().qos().periodNs());
        assertEquals(7400, node1.network().orElseThrow().listenAddress().getPort());
    }

    @Test
    void shouldDescribeNodeTwoAsTheControllerDialingNodeOne() throws Exception {
        Deployment node2 = new DeploymentReader().read(NODE2, Map.of("plant", "127.0.0.1:7500"));

        assertEquals("node2", node2.nodeId());
        assertEquals(List.of(PendulumController.DEFAULT_PROFILE), node2.components().stream()
                .map(Deployment.ComponentPlan::profile).toList());
        assertEquals(7500, node2.network().orElseThrow().peers().getFirst().getPort());
        assertTrue(node2.management().orElseThrow().accessList().getFirst().node().equals("node1"));
        var view = node2.view().orElseThrow().config();
        assertTrue(view.listen().getAddress().isLoopbackAddress() && !view.allowRemote(), view::toString);
        assertEquals(8080, view.listen().getPort());
    }

    @Test
    void shouldDescribeTheOneNodePendulum() throws Exception {
        Deployment one = new DeploymentReader().read(ONE_NODE);

        assertEquals(List.of(DspProxy.DEFAULT_PROFILE, PendulumController.DEFAULT_PROFILE), one.components().stream()
                .map(Deployment.ComponentPlan::profile).toList());
        assertTrue(one.network().isEmpty());
    }

    @Test
    void shouldNameThePortThatCannotBeOpenedBeforeAnythingStarts() throws Exception {
        Deployment one = new DeploymentReader().read(ONE_NODE, Map.of("port", "/dev/no-such-serial-port"));

        var e = assertThrows(DeploymentException.class, () -> DeployedNode.start(one).close());

        assertTrue(e.getMessage().contains("/dev/no-such-serial-port") && e.getMessage().contains("port"),
                e.getMessage());
        assertEquals(ONE_NODE, e.file());
    }

    @Test
    void shouldRefuseSimulatorSettingsForARealPort(@TempDir Path dir) throws Exception {
        // theta2 means nothing to a real board: a file that gives it with a port is a mistake.
        Path file = dir.resolve("real-port-with-theta2.xml");
        java.nio.file.Files.writeString(file, """
                <node id="n">
                  <scheduler type="fifo"/>
                  <component profile="dsp-proxy[pendulum=1]" class="io.etherware.examples.deploy.DspProxyFactory">
                    <setting name="port" value="/dev/ttyUSB9"/>
                    <setting name="theta2" value="0.05"/>
                  </component>
                </node>
                """);

        var e = assertThrows(DeploymentException.class, () -> DeployedNode.start(new DeploymentReader().read(file)));

        assertEquals(5, e.line(), e::getMessage);
        assertTrue(e.getMessage().contains("only the simulated board"), e.getMessage());
    }
}
