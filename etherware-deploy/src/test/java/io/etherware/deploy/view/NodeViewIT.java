package io.etherware.deploy.view;

import static org.junit.jupiter.api.Assertions.assertEquals;
import static org.junit.jupiter.api.Assertions.assertTrue;

import io.etherware.deploy.DeployedNode;
import io.etherware.deploy.DeploymentReader;
import io.etherware.deploy.fixtures.SignalingFactory;
import io.etherware.testkit.Await;
import java.net.InetSocketAddress;
import java.net.URI;
import java.net.http.HttpClient;
import java.net.http.HttpRequest;
import java.net.http.HttpResponse;
import java.nio.charset.StandardCharsets;
import java.nio.file.Files;
import java.nio.file.Path;
import java.time.Duration;
import java.util.Map;
import org.junit.jupiter.api.Test;
import org.junit.jupiter.api.io.TempDir;

/**
 * A deployed node with a {@code <view>} on a free loopback port, whose Notifier ticks a component
 * that publishes a live signal: its endpoints are read over real HTTP while it runs, as a browser
 * and a Prometheus scraper would.
 */
class NodeViewIT {

    private static final Duration TIMEOUT = Duration.ofSeconds(10);

    @TempDir
    Path dir;

    private final HttpClient http = HttpClient.newBuilder().connectTimeout(TIMEOUT).build();

    private HttpResponse<String> send(String method, URI uri) throws Exception {
        return http.send(HttpRequest.newBuilder(uri).timeout(TIMEOUT).method(method,
                HttpRequest.BodyPublishers.noBody()).build(), HttpResponse.BodyHandlers.ofString(StandardCharsets.UTF_8));
    }

    private Exposition scrape(URI base) throws Exception {
        HttpResponse<String> response = send("GET", base.resolve("/metrics"));
        assertEquals(200, response.statusCode());
        assertEquals("text/plain; version=0.0.4; charset=utf-8",
                response.headers().firstValue("Content-Type").orElse(""));
        return Exposition.parse(response.body());
    }

    @Test
    void shouldServeMetricsThatMoveWhileTheNodeRunsAndThePageAndStatus() throws Exception {
        Path file = dir.resolve("viewed.xml");
        Files.writeString(file, """
                <node id="viewed">
                  <scheduler type="realtime" holdCpuLatency="false"/>
                  <notifier>
                    <subscription name="tick" target="signaler" criticality="HIGH" period="5ms"/>
                  </notifier>
                  <component profile="signaler" class="%s"/>
                  <view listen="127.0.0.1:0"/>
                </node>
                """.formatted(SignalingFactory.class.getName()), StandardCharsets.UTF_8);

        try (DeployedNode deployed = DeployedNode.start(new DeploymentReader().read(file))) {
            InetSocketAddress address = deployed.viewAddress().orElseThrow();
            assertTrue(address.getAddress().isLoopbackAddress() && address.getPort() > 0, address::toString);
            URI base = URI.create(deployed.viewUrl().orElseThrow());
            var component = Map.of("node", "viewed", "component", "signaler");
            var signal = Map.of("node", "viewed", "signal", SignalingFactory.SIGNAL, "unit", "n");
            Await.until(() -> "the signaler handles a Tick", Await.DEADLINE_MS,
                    () -> deployed.signals().signals().getFirst().recorded() > 0);

            Exposition first = scrape(base);
            double handled = first.value("etherware_component_handled_total", component);
            double samples = first.value("etherware_signal_samples_total", signal);
            Await.until(() -> "more Ticks handled than the first scrape's " + handled, Await.DEADLINE_MS,
                    () -> deployed.signals().signals().getFirst().recorded() > samples + 2);
            Exposition second = scrape(base);

            assertTrue(handled >= 1, () -> "handled " + handled);
            assertTrue(second.value("etherware_component_handled_total", component) > handled,
                    () -> "handled did not grow: " + handled + " then " + second.samples);
            assertTrue(second.value("etherware_signal_samples_total", signal) > samples);
            assertEquals("gauge", second.types.get("etherware_signal_value"));
            assertTrue(second.value("etherware_signal_value", signal) >= 1);
            assertTrue(second.value("etherware_node_handled_total", Map.of("node", "viewed")) > 0);
            assertTrue(second.find("etherware_dispatcher_start_latency_seconds",
                    Map.of("dispatcher", "1", "quantile", "0.99")).isPresent(), second.samples::toString);

            HttpResponse<String> page = send("GET", base);
            assertEquals(200, page.statusCode());
            assertTrue(page.body().contains("<canvas") || page.body().contains("createElement(\"canvas\")")
                    || page.body().contains("el(\"canvas\")"), "the page draws plots");
            assertTrue(page.headers().firstValue("Content-Security-Policy").orElse("").contains("default-src 'none'"));
            assertTrue(!page.body().contains("<script src") && !page.body().contains("<link")
                    && !page.body().contains("@import") && !page.body().matches("(?s).*fetch\\(\"(https?:)?//.*"),
                    "the page loads nothing from elsewhere");

            HttpResponse<String> status = send("GET", base.resolve("/status.json"));
            assertEquals(200, status.statusCode());
            assertTrue(status.body().startsWith("{\"nodeId\":\"viewed\","), status.body());
            assertTrue(status.body().contains("{\"profile\":\"signaler\",\"state\":\"RUNNING\""), status.body());

            HttpResponse<String> signals = send("GET", base.resolve("/signals.json"));
            assertTrue(signals.body().contains("\"name\":\"" + SignalingFactory.SIGNAL + "\""), signals.body());

            HttpResponse<String> post = send("POST", base.resolve("/metrics"));
            assertEquals(405, post.statusCode());
            assertEquals("GET, HEAD", post.headers().firstValue("Allow").orElse(""));
            assertEquals(404, send("GET", base.resolve("/nothing-here")).statusCode());
            HttpResponse<String> head = send("HEAD", base.resolve("/metrics"));
            assertEquals(200, head.statusCode());
            assertEquals("", head.body());
        }
    }
}
