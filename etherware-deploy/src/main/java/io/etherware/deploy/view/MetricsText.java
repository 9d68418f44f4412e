package io.etherware.deploy.view;

import io.etherware.services.status.NodeStatus;
import java.util.ArrayList;
import java.util.List;
import java.util.function.Function;

/**
 * A node's status and live signals in the Prometheus text exposition format, version 0.0.4: one
 * {@code # HELP} and {@code # TYPE} per family, then its samples, every one labelled with the node.
 * Label values are escaped as the format says (backslash, double quote, line feed), and so is HELP
 * text (backslash, line feed). Times are in seconds, the format's base unit. Stateless.
 */
final class MetricsText {

    /** The {@code Content-Type} of the exposition. */
    static final String CONTENT_TYPE = "text/plain; version=0.0.4; charset=utf-8";

    private MetricsText() {
    }

    /** The exposition of {@code status} and {@code signals}. */
    static String of(NodeStatus status, List<LiveSignals.Signal> signals) {
        var out = new StringBuilder(4096);
        String node = label("node", status.nodeId());
        List<String> self = List.of(node);
        Function<String, String> nodeOnly = n -> n;

        family(out, "etherware_node_info", "gauge", "The node and its scheduler; always 1.", self,
                n -> n + "," + label("scheduler", status.scheduler()), n -> 1);
        NodeStatus.Counters counters = status.counters();
        family(out, "etherware_node_handled_total", "counter", "Messages the node's components handled without an"
                + " exception.", self, nodeOnly, n -> counters.handled());
        family(out, "etherware_node_failed_total", "counter", "Messages whose handling threw.", self, nodeOnly,
                n -> counters.failed());
        family(out, "etherware_node_restarts_total", "counter", "Component restarts by supervision.", self, nodeOnly,
                n -> counters.restarts());
        family(out, "etherware_node_undeliverable_total", "counter", "Messages that could not be delivered.", self,
                nodeOnly, n -> counters.undeliverable());
        family(out, "etherware_node_request_timeouts_total", "counter", "Requests that got no reply in time.", self,
                nodeOnly, n -> counters.requestTimeouts());
        family(out, "etherware_node_deadline_misses_total", "counter", "Jobs that completed after their deadline, all"
                + " dispatchers.", self, nodeOnly, n -> counters.deadlineMisses());

        List<NodeStatus.ComponentEntry> components = status.components();
        Function<NodeStatus.ComponentEntry, String> component = c -> node + "," + label("component", c.profile());
        family(out, "etherware_component_up", "gauge", "1 if the component runs, 0 otherwise; its state as a label.",
                components, c -> component.apply(c) + "," + label("state", c.state()),
                c -> c.state().equals("RUNNING") ? 1 : 0);
        family(out, "etherware_component_handled_total", "counter", "Messages the component handled without an"
                + " exception.", components, component, NodeStatus.ComponentEntry::handled);
        family(out, "etherware_component_failed_total", "counter", "Messages whose handling threw.", components,
                component, NodeStatus.ComponentEntry::failed);
        family(out, "etherware_component_restarts_total", "counter", "Restarts by the component's supervision.",
                components, component, NodeStatus.ComponentEntry::restarts);
        family(out, "etherware_component_deadline_misses_total", "counter", "The component's jobs that completed"
                + " after their deadline (real-time scheduler).", components, component,
                NodeStatus.ComponentEntry::deadlineMisses);
        family(out, "etherware_component_max_execution_seconds", "gauge", "The component's longest job (real-time"
                + " scheduler).", components, component, c -> c.maxExecutionNs() / 1e9);

        List<NodeStatus.DispatcherEntry> dispatchers = status.dispatchers();
        Function<NodeStatus.DispatcherEntry, String> dispatcher = d -> node + "," + label("dispatcher",
                Integer.toString(d.id()));
        if (!dispatchers.isEmpty()) {
            family(out, "etherware_dispatcher_jobs_total", "counter", "Jobs the dispatcher ran.", dispatchers,
                    dispatcher, NodeStatus.DispatcherEntry::jobsRun);
            family(out, "etherware_dispatcher_deadline_misses_total", "counter", "Jobs that completed after their"
                    + " deadline.", dispatchers, dispatcher, NodeStatus.DispatcherEntry::deadlineMisses);
            family(out, "etherware_dispatcher_queued_jobs", "gauge", "Jobs waiting in the dispatcher's queue"
                    + " (approximate).", dispatchers, dispatcher, NodeStatus.DispatcherEntry::queuedJobs);
            // A summary's quantiles: one sample per dispatcher and quantile, under one HELP and TYPE.
            var quantiles = new ArrayList<Quantile>();
            for (NodeStatus.DispatcherEntry d : dispatchers) {
                quantiles.add(new Quantile(dispatcher.apply(d), "0.5", d.p50Ns()));
                quantiles.add(new Quantile(dispatcher.apply(d), "0.99", d.p99Ns()));
            }
            family(out, "etherware_dispatcher_start_latency_seconds", "summary", "Release-to-start latency of the"
                    + " dispatcher's jobs since the node started.", quantiles,
                    q -> q.labels() + "," + label("quantile", q.quantile()), q -> q.valueNs() / 1e9);
            family(out, "etherware_dispatcher_start_latency_max_seconds", "gauge", "The largest release-to-start"
                    + " latency of the dispatcher's jobs since the node started.", dispatchers, dispatcher,
                    d -> d.maxNs() / 1e9);
        }

        List<NodeStatus.PeerEntry> peers = status.peers();
        Function<NodeStatus.PeerEntry, String> peer = p -> node + "," + label("peer", p.nodeId());
        if (!peers.isEmpty()) {
            family(out, "etherware_peer_connected", "gauge", "1 while a connection to the peer is up.", peers, peer,
                    p -> p.connected() ? 1 : 0);
            family(out, "etherware_peer_queued_messages", "gauge", "Messages waiting to be written to the peer.",
                    peers, peer, NodeStatus.PeerEntry::queued);
            // No sample before NetworkTime's first estimate, rather than a made-up 0.
            family(out, "etherware_peer_clock_offset_seconds", "gauge", "The peer's clock minus this node's, as"
                    + " NetworkTime estimates it (absent before the first estimate).", peers, peer,
                    p -> p.clockOffsetNs() == null ? null : p.clockOffsetNs() / 1e9);
            family(out, "etherware_peer_round_trip_seconds", "gauge", "Round trip of the best recent time probe.",
                    peers, peer, p -> p.roundTripNs() == null ? null : p.roundTripNs() / 1e9);
        }

        Function<LiveSignals.Signal, String> signal = x -> node + "," + label("signal", x.name()) + ","
                + label("unit", x.unit());
        if (!signals.isEmpty()) {
            family(out, "etherware_signal_value", "gauge", "The newest sample of each live signal a component"
                    + " publishes (NaN: none), in the signal's unit.", signals, signal, MetricsText::newest);
            family(out, "etherware_signal_samples_total", "counter", "Samples recorded into each live signal.",
                    signals, signal, LiveSignals.Signal::recorded);
        }
        return out.toString();
    }

    private record Quantile(String labels, String quantile, long valueNs) {
    }

    private static double newest(LiveSignals.Signal signal) {
        LiveSignals.Samples samples = signal.samples();
        return samples.size() == 0 ? Double.NaN : samples.values()[samples.size() - 1];
    }

    /**
     * One family: its HELP and TYPE, then a sample per item with the item's labels and value; an
     * item whose value is null has no sample. Whole numbers are written without a fraction.
     */
    private static <T> void family(StringBuilder out, String name, String type, String help, List<T> items,
            Function<? super T, String> labels, Function<? super T, ? extends Number> value) {
        out.append("# HELP ").append(name).append(' ').append(escapeHelp(help)).append('\n');
        out.append("# TYPE ").append(name).append(' ').append(type).append('\n');
        for (T item : items) {
            Number number = value.apply(item);
            if (number == null) {
                continue;
            }
            out.append(name).append('{').append(labels.apply(item)).append("} ");
            if (number instanceof Double || number instanceof Float) {
                out.append(number(number.doubleValue()));
            } else {
                out.append(number.longValue());
            }
            out.append('\n');
        }
    }

    /** {@code name="value"}, the value escaped. */
    static String label(String name, String value) {
        return name + "=\"" + escapeLabel(value) + "\"";
    }

    /** A label value as the format writes it: backslash, double quote and line feed escaped. */
    static String escapeLabel(String value) {
        return value.replace("\\", "\\\\").replace("\"", "\\\"").replace("\n", "\\n");
    }

    /** HELP text as the format writes it: backslash and line feed escaped. */
    static String escapeHelp(String text) {
        return text.replace("\\", "\\\\").replace("\n", "\\n");
    }

    /** A sample value: Go's float syntax, with {@code NaN}, {@code +Inf} and {@code -Inf}. */
    static String number(double value) {
        if (Double.isNaN(value)) {
            return "NaN";
        }
        if (Double.isInfinite(value)) {
            return value > 0 ? "+Inf" : "-Inf";
        }
        return Double.toString(value);
    }
}
