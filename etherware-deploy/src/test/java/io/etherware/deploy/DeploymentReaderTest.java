package io.etherware.deploy;

import static org.junit.jupiter.api.Assertions.assertEquals;
import static org.junit.jupiter.api.Assertions.assertThrows;
import static org.junit.jupiter.api.Assertions.assertTrue;

import io.etherware.core.message.Criticality;
import io.etherware.core.message.Profile;
import io.etherware.rt.platform.SchedulingPolicy;
import io.etherware.services.notifier.Subscription;
import java.io.IOException;
import java.nio.charset.StandardCharsets;
import java.nio.file.Files;
import java.nio.file.Path;
import java.util.Map;
import java.util.stream.Stream;
import org.junit.jupiter.api.Test;
import org.junit.jupiter.api.io.TempDir;
import org.junit.jupiter.params.ParameterizedTest;
import org.junit.jupiter.params.provider.Arguments;
import org.junit.jupiter.params.provider.MethodSource;

class DeploymentReaderTest {

    private static final String COUNTER = "io.etherware.deploy.fixtures.TickCounter";
    private static final String FACTORY = "io.etherware.deploy.fixtures.RecordingFactory";

    @TempDir
    Path dir;

    private Path write(String name, String text) throws IOException {
        Path file = dir.resolve(name);
        Files.writeString(file, text, StandardCharsets.UTF_8);
        return file;
    }

    @Test
    void shouldReadEveryElementOfAFullDeployment() throws Exception {
        Path file = write("full.xml", """
                <?xml version="1.0" encoding="UTF-8"?>
                <node id="node-a">
                  <scheduler type="realtime" lockMemory="false" holdCpuLatency="false" realtimeCpus="1">
                    <dispatcher policy="other"/>
                    <dispatcher policy="fifo" priority="75" cpus="1"/>
                    <dispatcher policy="fifo" priority="65"/>
                    <dispatcher policy="rr" priority="55"/>
                  </scheduler>
                  <notifier priority="90">
                    <subscription name="loop" target="counter[kind=test]" criticality="MIDDLE" period="2.5ms"/>
                  </notifier>
                  <component profile="counter[kind=test]" class="%s"/>
                  <component profile="recorder" class="%s">
                    <setting name="greeting" value="hello"/>
                  </component>
                  <network listen="127.0.0.1:0" lanes="1">
                    <peer address="127.0.0.1:7499"/>
                  </network>
                  <management allowUnauthenticatedLinks="true" settleWait="250ms">
                    <allow node="node-b" operations="MIGRATE UPGRADE" components="counter"/>
                  </management>
                  <view listen="127.0.0.1:0"/>
                </node>
                """.formatted(COUNTER, FACTORY));

        Deployment deployment = new DeploymentReader().read(file);

        assertEquals("node-a", deployment.nodeId());
        assertEquals("realtime", deployment.scheduler().type());
        String scheduler = deployment.scheduler().description();
        assertTrue(scheduler.contains("SCHED_FIFO/75") && scheduler.contains("SCHED_RR/55"), scheduler);
        var notifier = deployment.notifier().orElseThrow();
        assertEquals(SchedulingPolicy.FIFO, notifier.config().threadPolicy().policy());
        assertEquals(90, notifier.config().threadPolicy().priority());
        Subscription loop = notifier.subscriptions().getFirst();
        assertEquals(Profile.of("counter", "kind", "test"), loop.target());
        assertEquals(Criticality.MIDDLE, loop.qos().criticality());
        assertEquals(2_500_000L, loop.qos().periodNs());
        assertEquals(2, deployment.components().size());
        assertEquals(Profile.of("recorder"), deployment.components().get(1).profile());
        var network = deployment.network().orElseThrow();
        assertEquals(1, network.lanes());
        assertEquals(7499, network.peers().getFirst().getPort());
        var management = deployment.management().orElseThrow();
        assertEquals(1, management.accessList().size());
        assertEquals(250_000_000L, management.settleWaitNs());
        var view = deployment.view().orElseThrow();
        assertEquals(0, view.config().listen().getPort());
        assertEquals(22, view.line());
    }

    @Test
    void shouldDefaultToTableIIWithoutNotifierNetworkOrManagement() throws Exception {
        Path file = write("small.xml", """
                <node id="small"><component profile="counter" class="%s"/></node>
                """.formatted(COUNTER));

        Deployment deployment = new DeploymentReader().read(file);

        assertEquals("realtime", deployment.scheduler().type());
        assertTrue(deployment.scheduler().description().contains("Table II"), deployment.scheduler().description());
        assertTrue(deployment.notifier().isEmpty());
        assertTrue(deployment.network().isEmpty());
        assertTrue(deployment.management().isEmpty());
        assertTrue(deployment.view().isEmpty());
    }

    @Test
    void shouldDefaultTheViewToLoopbackPort8080() throws Exception {
        Path file = write("view.xml", """
                <node id="v"><component profile="counter" class="%s"/><view/></node>
                """.formatted(COUNTER));

        var view = new DeploymentReader().read(file).view().orElseThrow().config();

        assertTrue(view.listen().getAddress().isLoopbackAddress(), view::toString);
        assertEquals(8080, view.listen().getPort());
    }

    @Test
    void shouldReplacePropertiesAndTheirDefaults() throws Exception {
        Path file = write("props.xml", """
                <node id="${id}">
                  <component profile="counter" class="%s"/>
                  <network listen="${listen:-127.0.0.1:7400}"><peer address="${peer:-127.0.0.1:7401}"/></network>
                </node>
                """.formatted(COUNTER));

        Deployment deployment = new DeploymentReader().read(file, Map.of("id", "from-property",
                "peer", "127.0.0.1:7999"));

        assertEquals("from-property", deployment.nodeId());
        assertEquals(7400, deployment.network().orElseThrow().listenAddress().getPort());
        assertEquals(7999, deployment.network().orElseThrow().peers().getFirst().getPort());
    }

    @Test
    void shouldEscapeAPropertyRatherThanLetItWriteMarkup() throws Exception {
        Path file = write("escape.xml", """
                <node id="n">
                  <component profile="recorder" class="%s"><setting name="greeting" value="${text}"/></component>
                </node>
                """.formatted(FACTORY));

        // A value with quotes and markup stays one attribute value; it does not add an element.
        Deployment deployment = new DeploymentReader().read(file, Map.of("text", "a\"/><component profile=\"x"));

        assertEquals(1, deployment.components().size());
        assertEquals("a\"/><component profile=\"x", deployment.components().getFirst().settings().string("greeting"));
    }

    static Stream<Arguments> badFiles() {
        return Stream.of(
                Arguments.of("not well-formed", "<node id=\"n\">\n<component profile=\"a\" class=\"" + COUNTER
                        + "\">\n</node>", 3, new String[] {"component"}),
                Arguments.of("an unknown element", "<node id=\"n\">\n  <dispatchers/>\n</node>", 2,
                        new String[] {"dispatchers"}),
                Arguments.of("elements out of order", "<node id=\"n\">\n  <component profile=\"a\" class=\"" + COUNTER
                        + "\"/>\n  <notifier/>\n</node>", 3, new String[] {"notifier"}),
                Arguments.of("a missing node id", "<node>\n</node>", 1, new String[] {"id"}),
                Arguments.of("a duration without unit", "<node id=\"n\">\n<notifier>\n<subscription name=\"s\""
                        + " target=\"a\" period=\"15\"/>\n</notifier>\n</node>", 3,
                        new String[] {"15", "e.g. 15ms"}),
                Arguments.of("a bad profile", "<node id=\"n\">\n<component profile=\"a[b]\" class=\"" + COUNTER
                        + "\"/>\n</node>", 2, new String[] {"a[b]", "role[key=value"}),
                Arguments.of("a bad address", "<node id=\"n\">\n<network listen=\"localhost\"/>\n</node>", 2,
                        new String[] {"localhost", "'listen'", "'network'", "HOST:PORT"}),
                Arguments.of("three lanes", "<node id=\"n\">\n<network listen=\"127.0.0.1:0\" lanes=\"3\"/>\n</node>", 2,
                        new String[] {"'lanes'", "'network'", "1 or 2"}),
                Arguments.of("a profile with a key twice", "<node id=\"n\">\n<component profile=\"a[k=1,k=2]\""
                        + " class=\"" + COUNTER + "\"/>\n</node>", 2, new String[] {"'k' given twice"}),
                Arguments.of("two plugin directories", "<node id=\"n\">\n<management>\n<plugins directory=\"a\""
                        + " trustedSigner=\"a.pem\"/>\n<plugins directory=\"b\" trustedSigner=\"b.pem\"/>\n"
                        + "</management>\n</node>", 4, new String[] {"plugins"}),
                Arguments.of("a duration below a nanosecond", "<node id=\"n\">\n<management settleWait=\"0.2ns\"/>\n"
                        + "</node>", 2, new String[] {"at least 1ns"}),
                Arguments.of("a port above 65535", "<node id=\"n\">\n<network listen=\"127.0.0.1:70000\"/>\n</node>",
                        2, new String[] {"70000", "65535"}),
                Arguments.of("an unknown class", "<node id=\"n\">\n<component profile=\"a\""
                        + " class=\"com.example.Missing\"/>\n</node>", 2, new String[] {"com.example.Missing",
                            "class path"}),
                Arguments.of("a class that is no component", "<node id=\"n\">\n<component profile=\"a\""
                        + " class=\"io.etherware.deploy.fixtures.NotAComponent\"/>\n</node>", 2,
                        new String[] {"neither", "ComponentFactory"}),
                Arguments.of("settings for a plain component", "<node id=\"n\">\n<component profile=\"a\" class=\""
                        + COUNTER + "\">\n<setting name=\"x\" value=\"1\"/>\n</component>\n</node>", 3,
                        new String[] {"takes no settings"}),
                Arguments.of("two components with one profile", "<node id=\"n\">\n<component profile=\"a\" class=\""
                        + COUNTER + "\"/>\n<component profile=\"a\" class=\"" + COUNTER + "\"/>\n</node>", 3,
                        new String[] {"line 2", "its own profile"}),
                Arguments.of("a setting given twice", "<node id=\"n\">\n<component profile=\"a\" class=\"" + FACTORY
                        + "\">\n<setting name=\"greeting\" value=\"1\"/>\n<setting name=\"greeting\" value=\"2\"/>\n"
                        + "</component>\n</node>", 4, new String[] {"given twice", "line 3"}),
                Arguments.of("an undefined property", "<node id=\"n\">\n<network listen=\"${nowhere}\"/>\n</node>", 2,
                        new String[] {"${nowhere}", "-P nowhere=VALUE"}),
                Arguments.of("a DOCTYPE", "<?xml version=\"1.0\"?>\n<!DOCTYPE node [<!ENTITY x SYSTEM"
                        + " \"file:///etc/passwd\">]>\n<node id=\"&x;\"/>", 2, new String[] {"DOCTYPE"}),
                Arguments.of("dispatchers for the fifo scheduler", "<node id=\"n\">\n<scheduler type=\"fifo\">\n"
                        + "<dispatcher policy=\"fifo\" priority=\"80\"/>\n</scheduler>\n</node>", 3,
                        new String[] {"fifo scheduler has one ordinary thread"}),
                Arguments.of("a priority for an ordinary dispatcher", "<node id=\"n\">\n<scheduler>\n"
                        + "<dispatcher policy=\"other\" priority=\"10\"/>\n</scheduler>\n</node>", 3,
                        new String[] {"no real-time priority"}),
                Arguments.of("a real-time dispatcher without priority", "<node id=\"n\">\n<scheduler>\n"
                        + "<dispatcher policy=\"other\"/>\n<dispatcher policy=\"fifo\"/>\n</scheduler>\n</node>", 4,
                        new String[] {"needs a priority"}),
                Arguments.of("a priority out of range", "<node id=\"n\">\n<scheduler>\n"
                        + "<dispatcher policy=\"other\"/>\n<dispatcher policy=\"fifo\" priority=\"120\"/>\n</scheduler>"
                        + "\n</node>", 4, new String[] {"120", "1..99"}),
                Arguments.of("plain links beyond loopback", "<node id=\"n\">\n<network listen=\"127.0.0.1:0\">\n"
                        + "<peer address=\"192.0.2.1:7400\"/>\n</network>\n</node>", 2,
                        new String[] {"beyond loopback", "TLS", "insecure"}),
                Arguments.of("a TLS password file that is missing", "<node id=\"n\">\n<network"
                        + " listen=\"127.0.0.1:0\">\n<tls keyStore=\"k.p12\" keyStorePasswordFile=\"missing.txt\""
                        + " trustStore=\"t.p12\" trustStorePasswordFile=\"missing.txt\"/>\n</network>\n</node>", 3,
                        new String[] {"missing.txt", "password on one line"}),
                Arguments.of("a plugin directory that is missing", "<node id=\"n\">\n<management>\n<plugins"
                        + " directory=\"no-such-dir\" trustedSigner=\"signer.pem\"/>\n</management>\n</node>", 3,
                        new String[] {"no-such-dir", "create the directory"}),
                Arguments.of("an unknown operation", "<node id=\"n\">\n<management>\n<allow node=\"b\""
                        + " operations=\"DELETE\" components=\"*\"/>\n</management>\n</node>", 3,
                        new String[] {"DELETE"}),
                Arguments.of("a view beyond loopback", "<node id=\"n\">\n<component profile=\"a\" class=\""
                        + COUNTER + "\"/>\n<view listen=\"0.0.0.0:8080\"/>\n</node>", 3,
                        new String[] {"<view listen=\"0.0.0.0:8080\">", "beyond loopback", "allowRemote=\"true\""}),
                Arguments.of("two subscriptions with one name", "<node id=\"n\">\n<notifier>\n<subscription"
                        + " name=\"s\" target=\"a\" period=\"1ms\"/>\n<subscription name=\"s\" target=\"b\""
                        + " period=\"1ms\"/>\n</notifier>\n</node>", 4, new String[] {"given twice"}));
    }

    @ParameterizedTest(name = "{0}")
    @MethodSource("badFiles")
    void shouldNameTheLineAndTheProblemOfABadFile(String what, String text, int line, String[] mentions)
            throws IOException {
        Path file = write("bad.xml", text);

        var e = assertThrows(DeploymentException.class, () -> new DeploymentReader().read(file), what);

        assertEquals(line, e.line(), () -> what + ": " + e.getMessage());
        assertTrue(e.getMessage().startsWith(file + ":" + line), e.getMessage());
        for (String mention : mentions) {
            assertTrue(e.getMessage().contains(mention), () -> what + ": '" + mention + "' not in: " + e.getMessage());
        }
    }

    @Test
    void shouldRefuseAPropertyTheFileDoesNotUse() throws IOException {
        Path file = write("unused.xml", "<node id=\"n\"><network listen=\"${listen:-127.0.0.1:0}\"/></node>\n");

        var e = assertThrows(DeploymentException.class, () -> new DeploymentReader().read(file,
                Map.of("lisen", "127.0.0.1:1")));

        assertTrue(e.getMessage().contains("-P lisen") && e.getMessage().contains("[listen]"), e.getMessage());
    }

    @Test
    void shouldLeavePropertiesInCommentsAloneAndReadAByteOrderMarkAndOneAsTrue() throws Exception {
        Path file = write("comments.xml", "\uFEFF<!-- run with -P port=${port} -->\n<node id=\"n\">\n"
                + "<!-- a comment over\n two lines: ${other} -->\n<network listen=\"${listen:-127.0.0.1:0}\""
                + " lanes=\"1\" insecure=\"1\"/>\n</node>\n");

        Deployment deployment = new DeploymentReader().read(file);

        assertTrue(deployment.network().orElseThrow().insecure());
        assertEquals(1, deployment.network().orElseThrow().lanes());
    }

    @Test
    void shouldRefuseAFileThatIsNotThere() {
        Path file = dir.resolve("absent.xml");

        var e = assertThrows(DeploymentException.class, () -> new DeploymentReader().read(file));

        assertTrue(e.getMessage().contains("cannot be read"), e.getMessage());
    }

    @Test
    void shouldRefuseAFileThatIsNotUtf8() throws IOException {
        Path file = dir.resolve("latin1.xml");
        Files.write(file, new byte[] {'<', 'n', 'o', 'd', 'e', ' ', 'i', 'd', '=', '"', (byte) 0xE9, '"', '/', '>'});

        var e = assertThrows(DeploymentException.class, () -> new DeploymentReader().read(file));

        assertTrue(e.getMessage().contains("UTF-8"), e.getMessage());
    }
}
