package io.etherware.deploy;

import static org.junit.jupiter.api.Assertions.assertEquals;
import static org.junit.jupiter.api.Assertions.assertTrue;

import io.etherware.deploy.fixtures.TickCounter;
import io.etherware.testkit.Await;
import java.io.IOException;
import java.io.PrintWriter;
import java.io.StringWriter;
import java.net.InetAddress;
import java.net.ServerSocket;
import java.nio.charset.StandardCharsets;
import java.nio.file.Files;
import java.nio.file.Path;
import java.util.List;
import org.junit.jupiter.api.AfterAll;
import org.junit.jupiter.api.BeforeAll;
import org.junit.jupiter.api.Test;
import org.junit.jupiter.api.io.TempDir;
import picocli.CommandLine;

/**
 * The control tool against a node deployed in this JVM on loopback: its status as text and JSON,
 * an upgrade the node's access list allows, a migration it refuses, and a node that is not there.
 */
class ControlCommandIT {

    @TempDir
    static Path dir;

    private static DeployedNode deployed;
    private static String address;

    @BeforeAll
    static void deploy() throws Exception {
        Path file = dir.resolve("target.xml");
        Files.writeString(file, """
                <node id="target-node">
                  <notifier priority="1">
                    <subscription name="count" target="counter" criticality="MIDDLE" period="5ms"/>
                  </notifier>
                  <component profile="counter" class="io.etherware.deploy.fixtures.TickCounter"/>
                  <network listen="127.0.0.1:0"/>
                  <management allowUnauthenticatedLinks="true">
                    <allow node="control" operations="UPGRADE" components="counter"/>
                  </management>
                </node>
                """, StandardCharsets.UTF_8);
        deployed = DeployedNode.start(new DeploymentReader().read(file));
        var listen = deployed.listenAddress().orElseThrow();
        address = listen.getHostString() + ":" + listen.getPort();
    }

    @AfterAll
    static void close() {
        deployed.close();
    }

    private record Run(int exit, String out, String err) {
    }

    private static Run control(String... args) {
        var out = new StringWriter();
        var err = new StringWriter();
        int exit = new CommandLine(new ControlCommand()).setOut(new PrintWriter(out)).setErr(new PrintWriter(err))
                .execute(args);
        return new Run(exit, out.toString(), err.toString());
    }

    @Test
    void shouldListTheComponentsAndDispatchersOfTheNode() {
        TickCounter.RECEIVED.set(0);
        // The Notifier ticks the counter every 5 ms.
        Await.until("3 Ticks counted", () -> TickCounter.RECEIVED.get() >= 3);

        Run run = control("--node", address, "status");

        assertEquals(0, run.exit(), run::toString);
        assertTrue(run.out().startsWith("node target-node  scheduler realtime"), run.out());
        String counterRow = run.out().lines().filter(line -> line.startsWith("counter ")).findFirst()
                .orElseThrow(() -> new AssertionError(run.out()));
        assertTrue(counterRow.contains("RUNNING") && counterRow.matches(".*TickCounter(V2)?"), counterRow); // V2 after the upgrade test
        long handled = Long.parseLong(counterRow.trim().split("\\s+")[2]);
        assertTrue(handled >= 3, counterRow);
        assertTrue(run.out().contains("DISPATCHER") && run.out().contains("START p50 µs"), run.out());
        assertTrue(run.out().contains("control") && run.out().contains("yes"), "the tool is a connected peer: "
                + run.out());
    }

    @Test
    void shouldPrintTheStatusAsJson() {
        Run run = control("--node", address, "--json", "status");

        assertEquals(0, run.exit(), run::toString);
        String json = run.out().strip();
        assertTrue(json.startsWith("{\"nodeId\":\"target-node\",") && json.endsWith("}"), json);
        assertTrue(json.contains("\"profile\":\"counter\"") && json.contains("\"dispatchers\":[{\"id\":0"), json);
    }

    @Test
    void shouldUpgradeWhatTheAccessListAllowsAndPrintTheAnswer() {
        Run run = control("--node", address, "upgrade", "--component", "counter", "--class",
                "io.etherware.deploy.fixtures.TickCounterV2");

        assertEquals(0, run.exit(), run::toString);
        assertTrue(run.out().startsWith("upgraded counter on target-node: " + TickCounter.class.getName() + " -> "
                + "io.etherware.deploy.fixtures.TickCounterV2"), run.out());
        Run after = control("--node", address, "status");
        assertTrue(after.out().lines().anyMatch(line -> line.startsWith("counter ") && line.endsWith("TickCounterV2")),
                after.out());
    }

    @Test
    void shouldPrintTheRefusalOfAMigrationTheAccessListDoesNotAllow() {
        Run run = control("--node", address, "--json", "migrate", "--component", "counter", "--to", "elsewhere");

        assertEquals(ControlCommand.FAILED, run.exit(), run::toString);
        assertTrue(run.out().startsWith("{\"result\":\"failed\",\"operation\":\"migrate\""), run.out());
        assertTrue(run.out().contains("\"reason\":\"REMOTE_REFUSED\""), run.out());
    }

    @Test
    void shouldSayNoNodeAnsweredWhenTheNodeIsNotThere() throws IOException {
        int port;
        try (var socket = new ServerSocket(0, 1, InetAddress.getLoopbackAddress())) {
            port = socket.getLocalPort(); // free once closed: nothing listens there
        }

        Run run = control("--node", "127.0.0.1:" + port, "--timeout", "1s", "status");

        assertEquals(ControlCommand.FAILED, run.exit(), run::toString);
        assertTrue(run.err().contains("no node answered at 127.0.0.1:" + port + " within 1000 ms"), run.err());
        assertEquals("", run.out());
    }

    @Test
    void shouldRefuseABadIdOrLaneCountAsAUsageError() {
        Run badId = control("--node", address, "--id", "a b", "status");
        Run badLanes = control("--node", address, "--lanes", "3", "status");

        assertEquals(2, badId.exit(), badId::toString);
        assertTrue(badId.err().contains("--id=a b"), badId.err());
        assertEquals(2, badLanes.exit(), badLanes::toString);
        assertTrue(badLanes.err().contains("--lanes=3"), badLanes.err());
    }

    @Test
    void shouldRefuseABadAddressAsAUsageError() {
        for (String bad : List.of("127.0.0.1", "127.0.0.1:http")) {
            Run run = control("--node", bad, "status");

            assertEquals(2, run.exit(), run::toString);
            assertTrue(run.err().contains("is not HOST:PORT"), run.err());
        }
    }
}
