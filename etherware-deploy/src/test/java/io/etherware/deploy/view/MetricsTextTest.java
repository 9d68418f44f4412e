package io.etherware.deploy.view;

import static org.junit.jupiter.api.Assertions.assertEquals;
import static org.junit.jupiter.api.Assertions.assertFalse;
import static org.junit.jupiter.api.Assertions.assertTrue;

import io.etherware.services.status.NodeStatus;
import java.util.List;
import java.util.Map;
import org.junit.jupiter.api.Test;

class MetricsTextTest {

    private static NodeStatus status(String nodeId, String profile) {
        return new NodeStatus(nodeId, 1L, "realtime [SCHED_OTHER, SCHED_FIFO/80]",
                List.of(new NodeStatus.ComponentEntry(profile, "RUNNING", "a.B", 42, 1, 2, 3, 1_500_000)),
                List.of(new NodeStatus.DispatcherEntry(1, 100, 4, 0, 12_000, 250_000, 3_000_000)),
                List.of(new NodeStatus.PeerEntry("node2", true, "127.0.0.1:7401", 0, 3, -2_500L, 90_000L),
                        new NodeStatus.PeerEntry("node3", false, "", 5, 0, null, null)),
                new NodeStatus.Counters(42, 1, 2, 7, 0, 4));
    }

    @Test
    void shouldWriteEveryFamilyTypedAndEverySampleLabelledWithTheNode() {
        var signals = new LiveSignals(4);
        signals.create("theta2", "rad").record(10, 0.0125);
        signals.create("u", "N·m");

        var parsed = Exposition.parse(MetricsText.of(status("node1", "controller[pendulum=1]"), signals.signals()));

        var controller = Map.of("node", "node1", "component", "controller[pendulum=1]");
        assertEquals(42, parsed.value("etherware_component_handled_total", controller));
        assertEquals("counter", parsed.types.get("etherware_component_handled_total"));
        assertEquals(3, parsed.value("etherware_component_deadline_misses_total", controller));
        assertEquals(0.0015, parsed.value("etherware_component_max_execution_seconds", controller), 1e-12);
        var dispatcher = Map.of("node", "node1", "dispatcher", "1");
        assertEquals(0.25e-3, parsed.value("etherware_dispatcher_start_latency_seconds",
                Map.of("dispatcher", "1", "quantile", "0.99")), 1e-12);
        assertEquals(12e-6, parsed.value("etherware_dispatcher_start_latency_seconds",
                Map.of("dispatcher", "1", "quantile", "0.5")), 1e-12);
        assertEquals("summary", parsed.types.get("etherware_dispatcher_start_latency_seconds"));
        assertEquals(4, parsed.value("etherware_dispatcher_deadline_misses_total", dispatcher));
        assertEquals(-2.5e-6, parsed.value("etherware_peer_clock_offset_seconds", Map.of("peer", "node2")), 1e-15);
        // Before NetworkTime's first estimate there is no offset to report, rather than a made-up 0.
        assertTrue(parsed.find("etherware_peer_clock_offset_seconds", Map.of("peer", "node3")).isEmpty());
        assertEquals(0, parsed.value("etherware_peer_connected", Map.of("peer", "node3")));
        assertEquals(7, parsed.value("etherware_node_undeliverable_total", Map.of("node", "node1")));
        assertEquals(0.0125, parsed.value("etherware_signal_value", Map.of("signal", "theta2", "unit", "rad")));
        assertTrue(Double.isNaN(parsed.value("etherware_signal_value", Map.of("signal", "u", "unit", "N·m"))));
        assertEquals(1, parsed.value("etherware_signal_samples_total", Map.of("signal", "theta2")));
        for (Exposition.Sample sample : parsed.samples) {
            assertEquals("node1", sample.labels().get("node"), sample::toString);
        }
    }

    @Test
    void shouldEscapeLabelValuesAndHelpAsTheFormatSays() {
        String awkward = "odd\\id \"quoted\"\nnext";
        String text = MetricsText.of(status(awkward, "p[k=v]"), List.of());

        assertTrue(text.contains("node=\"odd\\\\id \\\"quoted\\\"\\nnext\""), text);
        assertFalse(text.lines().anyMatch(line -> line.equals("next\"")), "a raw line feed split a sample");
        var parsed = Exposition.parse(text);
        assertEquals(awkward, parsed.find("etherware_node_handled_total", Map.of()).orElseThrow().labels()
                .get("node"));
        assertEquals("a\\\\b\\nc", MetricsText.escapeHelp("a\\b\nc"));
    }

    @Test
    void shouldWriteNonFiniteValuesInGoSyntax() {
        assertEquals("NaN", MetricsText.number(Double.NaN));
        assertEquals("+Inf", MetricsText.number(Double.POSITIVE_INFINITY));
        assertEquals("-Inf", MetricsText.number(Double.NEGATIVE_INFINITY));
        assertEquals(1.5e-7, Double.parseDouble(MetricsText.number(1.5e-7)));
    }
}
