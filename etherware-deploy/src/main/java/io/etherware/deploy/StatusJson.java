package io.etherware.deploy;

import io.etherware.services.management.ManagementFailure;
import io.etherware.services.management.MigrationResult;
import io.etherware.services.management.UpgradeResult;
import io.etherware.services.status.NodeStatus;
import java.util.List;
import java.util.function.Function;

/**
 * JSON of a node's status and of management answers, for scripts (the control tool's
 * {@code --json}): one object, numbers as JSON numbers (nanoseconds as integers), null where a
 * figure is not known yet. Written by hand with RFC 8259 string escaping; no dependency. Stateless.
 */
public final class StatusJson {

    private StatusJson() {
    }

    /**
     * A node's status as JSON.
     *
     * @param status the status
     * @return one JSON object
     */
    public static String format(NodeStatus status) {
        var c = status.counters();
        return "{\"nodeId\":" + string(status.nodeId()) + ",\"epochNs\":" + status.epochNs() + ",\"scheduler\":"
                + string(status.scheduler()) + ",\"counters\":{\"handled\":" + c.handled() + ",\"failed\":" + c.failed()
                + ",\"restarts\":" + c.restarts() + ",\"undeliverable\":" + c.undeliverable() + ",\"requestTimeouts\":"
                + c.requestTimeouts() + ",\"deadlineMisses\":" + c.deadlineMisses() + "},\"components\":"
                + array(status.components(), e -> "{\"profile\":" + string(e.profile()) + ",\"state\":"
                        + string(e.state()) + ",\"logic\":" + string(e.logic()) + ",\"handled\":" + e.handled()
                        + ",\"failed\":" + e.failed() + ",\"restarts\":" + e.restarts() + ",\"deadlineMisses\":"
                        + e.deadlineMisses() + ",\"maxExecutionNs\":" + e.maxExecutionNs() + "}")
                + ",\"dispatchers\":" + array(status.dispatchers(), d -> "{\"id\":" + d.id() + ",\"jobsRun\":"
                        + d.jobsRun() + ",\"deadlineMisses\":" + d.deadlineMisses() + ",\"queuedJobs\":"
                        + d.queuedJobs() + ",\"startLatencyP50Ns\":" + d.p50Ns() + ",\"startLatencyP99Ns\":" + d.p99Ns()
                        + ",\"startLatencyMaxNs\":" + d.maxNs() + "}")
                + ",\"peers\":" + array(status.peers(), p -> "{\"nodeId\":" + string(p.nodeId()) + ",\"connected\":"
                        + p.connected() + ",\"remote\":" + string(p.remote()) + ",\"queued\":" + p.queued()
                        + ",\"profiles\":" + p.profiles() + ",\"clockOffsetNs\":" + p.clockOffsetNs()
                        + ",\"roundTripNs\":" + p.roundTripNs() + "}")
                + "}";
    }

    static String format(String nodeId, UpgradeResult r) {
        return "{\"result\":\"upgraded\",\"node\":" + string(nodeId) + ",\"target\":" + string(r.target().toString())
                + ",\"oldImplementation\":" + string(r.oldImplementation()) + ",\"newImplementation\":"
                + string(r.newImplementation()) + ",\"source\":" + string(r.source()) + ",\"stateSchemaVersion\":"
                + r.stateSchemaVersion() + ",\"loadNs\":" + r.loadNs() + ",\"pauseNs\":" + r.pauseNs() + ",\"gapNs\":"
                + r.gapNs() + ",\"totalNs\":" + r.totalNs() + "}";
    }

    static String format(MigrationResult r) {
        return "{\"result\":\"migrated\",\"target\":" + string(r.target().toString()) + ",\"fromNode\":"
                + string(r.fromNode()) + ",\"toNode\":" + string(r.toNode()) + ",\"implementation\":"
                + string(r.implementation()) + ",\"stateSchemaVersion\":" + r.stateSchemaVersion()
                + ",\"heldMessages\":" + r.heldMessages() + ",\"prepareNs\":" + r.prepareNs() + ",\"quiesceNs\":"
                + r.quiesceNs() + ",\"transferNs\":" + r.transferNs() + ",\"relocateNs\":" + r.relocateNs()
                + ",\"gapNs\":" + r.gapNs() + ",\"totalNs\":" + r.totalNs() + "}";
    }

    static String format(ManagementFailure f) {
        return "{\"result\":\"failed\",\"operation\":" + string(f.operation()) + ",\"target\":"
                + string(f.target().toString()) + ",\"reason\":" + string(f.reason().name()) + ",\"error\":"
                + string(f.error()) + "}";
    }

    private static <T> String array(List<T> items, Function<T, String> element) {
        var out = new StringBuilder("[");
        for (T item : items) {
            if (out.length() > 1) {
                out.append(',');
            }
            out.append(element.apply(item));
        }
        return out.append(']').toString();
    }

    /**
     * {@code text} as a JSON string literal: quotes, backslashes and control characters escaped, and
     * {@code <}, {@code >} and {@code &} too, so that no value can close a {@code <script>} or open a
     * tag in a page it is pasted into.
     *
     * @param text the text, or null
     * @return the literal, or {@code null}
     */
    public static String string(String text) {
        if (text == null) {
            return "null";
        }
        var out = new StringBuilder(text.length() + 2).append('"');
        for (int i = 0; i < text.length(); i++) {
            char ch = text.charAt(i);
            switch (ch) {
                case '"' -> out.append("\\\"");
                case '\\' -> out.append("\\\\");
                case '\n' -> out.append("\\n");
                case '\r' -> out.append("\\r");
                case '\t' -> out.append("\\t");
                default -> {
                    if (ch < 0x20 || ch == 0x2028 || ch == 0x2029 || ch == '<' || ch == '>' || ch == '&') {
                        out.append(String.format("\\u%04x", (int) ch));
                    } else {
                        out.append(ch);
                    }
                }
            }
        }
        return out.append('"').toString();
    }
}
