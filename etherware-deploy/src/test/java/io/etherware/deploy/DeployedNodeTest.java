package io.etherware.deploy;

import static org.junit.jupiter.api.Assertions.assertEquals;
import static org.junit.jupiter.api.Assertions.assertThrows;
import static org.junit.jupiter.api.Assertions.assertTrue;

import io.etherware.deploy.fixtures.RecordingFactory;
import io.etherware.deploy.fixtures.TickCounter;
import io.etherware.testkit.Await;
import java.io.IOException;
import java.nio.charset.StandardCharsets;
import java.nio.file.Files;
import java.nio.file.Path;
import java.util.List;
import org.junit.jupiter.api.BeforeEach;
import org.junit.jupiter.api.Test;
import org.junit.jupiter.api.io.TempDir;

/** A node started from a file, with the original scheduler (ordinary threads) and no network. */
class DeployedNodeTest {

    @TempDir
    Path dir;

    @BeforeEach
    void reset() {
        RecordingFactory.EVENTS.clear();
        TickCounter.RECEIVED.set(0);
    }

    private Deployment read(String text) throws IOException, DeploymentException {
        Path file = dir.resolve("node.xml");
        Files.writeString(file, text, StandardCharsets.UTF_8);
        return new DeploymentReader().read(file);
    }

    @Test
    void shouldTickALocalComponentAndCloseTheNodeBeforeTheResources() throws Exception {
        Deployment deployment = read("""
                <node id="local">
                  <scheduler type="fifo"/>
                  <notifier priority="1">
                    <subscription name="count" target="counter" criticality="HIGH" period="2ms"/>
                  </notifier>
                  <component profile="counter" class="io.etherware.deploy.fixtures.TickCounter"/>
                  <component profile="first" class="io.etherware.deploy.fixtures.RecordingFactory">
                    <setting name="greeting" value="first"/>
                  </component>
                  <component profile="second" class="io.etherware.deploy.fixtures.RecordingFactory">
                    <setting name="greeting" value="second"/>
                  </component>
                </node>
                """);

        try (DeployedNode deployed = DeployedNode.start(deployment)) {
            assertTrue(deployed.node().isRunning());
            Await.until(() -> "5 Ticks; received: " + TickCounter.RECEIVED.get(), Await.DEADLINE_MS,
                    () -> TickCounter.RECEIVED.get() >= 5);
        }

        // The components stop with the node; their resources close after it, the last opened first.
        List<String> events = List.copyOf(RecordingFactory.EVENTS);
        assertEquals(4, events.size(), events::toString);
        assertTrue(events.subList(0, 2).containsAll(List.of("component first stopped", "component second stopped")),
                events::toString);
        assertEquals(List.of("resource second closed", "resource first closed"), events.subList(2, 4));
    }

    @Test
    void shouldNameAMisspeltSettingAndCloseWhatWasOpened() throws Exception {
        Deployment deployment = read("""
                <node id="typo">
                  <scheduler type="fifo"/>
                  <component profile="first" class="io.etherware.deploy.fixtures.RecordingFactory">
                    <setting name="greeting" value="first"/>
                  </component>
                  <component profile="second" class="io.etherware.deploy.fixtures.RecordingFactory">
                    <setting name="greeting" value="second"/>
                    <setting name="greting" value="oops"/>
                  </component>
                </node>
                """);

        var e = assertThrows(DeploymentException.class, () -> DeployedNode.start(deployment));

        assertEquals(8, e.line(), e::getMessage);
        assertTrue(e.getMessage().contains("greting") && e.getMessage().contains("check the spelling"),
                e.getMessage());
        assertEquals(List.of("resource second closed", "resource first closed"), RecordingFactory.EVENTS);
    }

    @Test
    void shouldReportAFactoryThatRefusesItsSettingsAndCloseWhatWasOpened() throws Exception {
        Deployment deployment = read("""
                <node id="refused">
                  <scheduler type="fifo"/>
                  <component profile="first" class="io.etherware.deploy.fixtures.RecordingFactory">
                    <setting name="greeting" value="first"/>
                    <setting name="fail" value="true"/>
                  </component>
                </node>
                """);

        var e = assertThrows(DeploymentException.class, () -> DeployedNode.start(deployment));

        assertEquals(5, e.line(), e::getMessage);
        assertTrue(e.getMessage().contains("asked to fail"), e.getMessage());
        assertEquals(List.of("resource first closed"), RecordingFactory.EVENTS);
    }

    @Test
    void shouldNameAMissingRequiredSetting() throws Exception {
        Deployment deployment = read("""
                <node id="missing">
                  <scheduler type="fifo"/>
                  <component profile="first" class="io.etherware.deploy.fixtures.RecordingFactory"/>
                </node>
                """);

        var e = assertThrows(DeploymentException.class, () -> DeployedNode.start(deployment));

        assertEquals(3, e.line(), e::getMessage);
        assertTrue(e.getMessage().contains("needs <setting name=\"greeting\""), e.getMessage());
    }
}
