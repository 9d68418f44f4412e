package io.etherware.deploy.view;

import io.etherware.services.status.NodeStatus;
import java.util.List;

/**
 * The view's JSON documents, written by hand (the module needs no JSON library for two small
 * documents): {@code /status.json}, a {@link NodeStatus} field for field, and
 * {@code /signals.json}, every live signal's samples. Strings are escaped per RFC 8259; a
 * non-finite number is written as {@code null}. Stateless.
 */
final class ViewJson {

    private ViewJson() {
    }

    /** A {@link NodeStatus} as a JSON object; times in nanoseconds, as the record has them. */
    static String status(NodeStatus status) {
        var out = new StringBuilder(1024);
        out.append("{\"nodeId\":");
        string(out, status.nodeId());
        out.append(",\"epochNs\":").append(status.epochNs()).append(",\"scheduler\":");
        string(out, status.scheduler());
        out.append(",\"components\":[");
        List<NodeStatus.ComponentEntry> components = status.components();
        for (int i = 0; i < components.size(); i++) {
            NodeStatus.ComponentEntry c = components.get(i);
            out.append(i == 0 ? "{" : ",{").append("\"profile\":");
            string(out, c.profile());
            out.append(",\"state\":");
            string(out, c.state());
            out.append(",\"logic\":");
            string(out, c.logic());
            out.append(",\"handled\":").append(c.handled()).append(",\"failed\":").append(c.failed())
                    .append(",\"restarts\":").append(c.restarts()).append(",\"deadlineMisses\":")
                    .append(c.deadlineMisses()).append(",\"maxExecutionNs\":").append(c.maxExecutionNs()).append('}');
        }
        out.append("],\"dispatchers\":[");
        List<NodeStatus.DispatcherEntry> dispatchers = status.dispatchers();
        for (int i = 0; i < dispatchers.size(); i++) {
            NodeStatus.DispatcherEntry d = dispatchers.get(i);
            out.append(i == 0 ? "{" : ",{").append("\"id\":").append(d.id()).append(",\"jobsRun\":")
                    .append(d.jobsRun()).append(",\"deadlineMisses\":").append(d.deadlineMisses())
                    .append(",\"queuedJobs\":").append(d.queuedJobs()).append(",\"p50Ns\":").append(d.p50Ns())
                    .append(",\"p99Ns\":").append(d.p99Ns()).append(",\"maxNs\":").append(d.maxNs()).append('}');
        }
        out.append("],\"peers\":[");
        List<NodeStatus.PeerEntry> peers = status.peers();
        for (int i = 0; i < peers.size(); i++) {
            NodeStatus.PeerEntry p = peers.get(i);
            out.append(i == 0 ? "{" : ",{").append("\"nodeId\":");
            string(out, p.nodeId());
            out.append(",\"connected\":").append(p.connected()).append(",\"remote\":");
            string(out, p.remote());
            out.append(",\"queued\":").append(p.queued()).append(",\"profiles\":").append(p.profiles())
                    .append(",\"clockOffsetNs\":").append(p.clockOffsetNs()).append(",\"roundTripNs\":")
                    .append(p.roundTripNs()).append('}');
        }
        NodeStatus.Counters n = status.counters();
        out.append("],\"counters\":{\"handled\":").append(n.handled()).append(",\"failed\":").append(n.failed())
                .append(",\"restarts\":").append(n.restarts()).append(",\"undeliverable\":").append(n.undeliverable())
                .append(",\"requestTimeouts\":").append(n.requestTimeouts()).append(",\"deadlineMisses\":")
                .append(n.deadlineMisses()).append("}}");
        return out.toString();
    }

    /**
     * Every signal's samples: {@code {"signals":[{"name":..,"unit":..,"recorded":..,"t":[..],"v":[..]}]}},
     * {@code t} in seconds before the signal's newest sample (so the last is 0), {@code v} the
     * values ({@code null} for none).
     */
    static String signals(List<LiveSignals.Signal> signals) {
        var out = new StringBuilder(256 + signals.size() * 24 * 1024);
        out.append("{\"signals\":[");
        for (int i = 0; i < signals.size(); i++) {
            LiveSignals.Signal signal = signals.get(i);
            LiveSignals.Samples samples = signal.samples();
            out.append(i == 0 ? "{" : ",{").append("\"name\":");
            string(out, signal.name());
            out.append(",\"unit\":");
            string(out, signal.unit());
            out.append(",\"recorded\":").append(signal.recorded()).append(",\"t\":[");
            long newestNs = samples.size() == 0 ? 0 : samples.timesNs()[samples.size() - 1];
            for (int k = 0; k < samples.size(); k++) {
                if (k > 0) {
                    out.append(',');
                }
                // Milliseconds' resolution is plenty for a plot, and keeps the document small.
                number(out, Math.round((samples.timesNs()[k] - newestNs) / 1e6) / 1e3);
            }
            out.append("],\"v\":[");
            for (int k = 0; k < samples.size(); k++) {
                if (k > 0) {
                    out.append(',');
                }
                // Seven significant digits (a float's) are more than a plot or an encoder resolves.
                float value = (float) samples.values()[k];
                if (Float.isFinite(value)) {
                    out.append(value);
                } else {
                    out.append("null");
                }
            }
            out.append("]}");
        }
        return out.append("]}").toString();
    }

    /** Appends {@code text} as a JSON string: quoted, with quotes, backslashes and controls escaped. */
    static void string(StringBuilder out, String text) {
        out.append('"');
        for (int i = 0; i < text.length(); i++) {
            char c = text.charAt(i);
            switch (c) {
                case '"' -> out.append("\\\"");
                case '\\' -> out.append("\\\\");
                case '\n' -> out.append("\\n");
                case '\r' -> out.append("\\r");
                case '\t' -> out.append("\\t");
                case '\b' -> out.append("\\b");
                case '\f' -> out.append("\\f");
                // '<' too, so that a value can never close a <script> it is pasted into.
                case '<', '>', '&', '\u2028', '\u2029' -> out.append(String.format("\\u%04x", (int) c));
                default -> {
                    if (c < 0x20) {
                        out.append(String.format("\\u%04x", (int) c));
                    } else {
                        out.append(c);
                    }
                }
            }
        }
        out.append('"');
    }

    /** Appends {@code value} as a JSON number, or {@code null} for NaN and infinities. */
    static void number(StringBuilder out, double value) {
        if (Double.isFinite(value)) {
            out.append(value);
        } else {
            out.append("null");
        }
    }
}
