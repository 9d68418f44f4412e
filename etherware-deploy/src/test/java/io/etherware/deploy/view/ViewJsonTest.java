package io.etherware.deploy.view;

import static org.junit.jupiter.api.Assertions.assertEquals;
import static org.junit.jupiter.api.Assertions.assertTrue;

import io.etherware.services.status.NodeStatus;
import java.util.List;
import org.junit.jupiter.api.Test;

class ViewJsonTest {

    private static String string(String text) {
        var out = new StringBuilder();
        ViewJson.string(out, text);
        return out.toString();
    }

    @Test
    void shouldEscapeQuotesBackslashesControlsAndMarkup() {
        assertEquals("\"a\\\"b\\\\c\\nd\\te\\u0001\"", string("a\"b\\c\nd\te\u0001"));
        // '<' and '>' escaped so that no value can close a <script> or open a tag it is pasted into.
        assertEquals("\"\\u003c/script\\u003e\"", string("</script>"));
        assertEquals("\"θ2 N·m\"", string("θ2 N·m"));
    }

    @Test
    void shouldWriteTheStatusWithNullsForMissingEstimates() {
        var status = new NodeStatus("n\"1", 5L, "fifo", List.of(new NodeStatus.ComponentEntry("c[k=v]", "RUNNING",
                "x.Y", 1, 0, 0, 0, 0)), List.of(), List.of(new NodeStatus.PeerEntry("n2", false, "", 0, 0, null,
                null)), new NodeStatus.Counters(1, 0, 0, 0, 0, 0));

        String json = ViewJson.status(status);

        assertTrue(json.startsWith("{\"nodeId\":\"n\\\"1\",\"epochNs\":5,"), json);
        assertTrue(json.contains("\"clockOffsetNs\":null,\"roundTripNs\":null"), json);
        assertTrue(json.contains("\"dispatchers\":[]"), json);
        assertTrue(json.contains("\"counters\":{\"handled\":1,") && json.endsWith("}]}"), json);
    }

    @Test
    void shouldWriteSamplesRelativeToTheNewestWithNullForNone() {
        var signals = new LiveSignals(8);
        LiveSignals.Signal u = signals.create("u", "N·m");
        u.record(1_000_000_000L, 0.5);
        u.record(1_250_000_000L, Double.NaN);
        u.record(1_500_000_000L, -0.25);

        String json = ViewJson.signals(signals.signals());

        assertEquals("{\"signals\":[{\"name\":\"u\",\"unit\":\"N·m\",\"recorded\":3,\"t\":[-0.5,-0.25,0.0],"
                + "\"v\":[0.5,null,-0.25]}]}", json);
    }
}
