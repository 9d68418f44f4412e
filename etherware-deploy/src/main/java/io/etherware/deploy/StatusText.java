package io.etherware.deploy;

import io.etherware.services.management.ManagementFailure;
import io.etherware.services.management.MigrationResult;
import io.etherware.services.management.UpgradeResult;
import io.etherware.services.status.NodeStatus;
import java.util.ArrayList;
import java.util.List;
import java.util.Locale;

/** The control tool's text output: aligned tables, times in µs. Stateless. */
final class StatusText {

    private StatusText() {
    }

    static String format(NodeStatus status) {
        var out = new StringBuilder();
        out.append("node ").append(status.nodeId()).append("  scheduler ").append(status.scheduler()).append('\n');
        NodeStatus.Counters c = status.counters();
        out.append(String.format(Locale.ROOT, "handled %d, failed %d, restarts %d, undeliverable %d, request timeouts"
                + " %d, deadline misses %d%n", c.handled(), c.failed(), c.restarts(), c.undeliverable(),
                c.requestTimeouts(), c.deadlineMisses()));
        out.append('\n');
        var nodes = new ArrayList<List<String>>();
        nodes.add(List.of("NODE", "CONNECTED", "ADDRESS", "QUEUED", "PROFILES", "CLOCK OFFSET µs", "RTT µs"));
        nodes.add(List.of(status.nodeId() + " (asked)", "-", "-", "-", "-", "-", "-"));
        for (NodeStatus.PeerEntry peer : status.peers()) {
            nodes.add(List.of(peer.nodeId(), peer.connected() ? "yes" : "no", peer.remote().isEmpty() ? "-"
                    : peer.remote(), Integer.toString(peer.queued()), Integer.toString(peer.profiles()),
                    signedMicros(peer.clockOffsetNs()), micros(peer.roundTripNs())));
        }
        table(out, nodes);
        out.append('\n');
        var components = new ArrayList<List<String>>();
        components.add(List.of("COMPONENT", "STATE", "HANDLED", "FAILED", "RESTARTS", "MISSES", "MAX EXEC µs", "LOGIC"));
        for (NodeStatus.ComponentEntry component : status.components()) {
            components.add(List.of(component.profile(), component.state(), Long.toString(component.handled()),
                    Long.toString(component.failed()), Long.toString(component.restarts()),
                    Long.toString(component.deadlineMisses()), micros(component.maxExecutionNs()), component.logic()));
        }
        table(out, components);
        if (!status.dispatchers().isEmpty()) {
            out.append('\n');
            var dispatchers = new ArrayList<List<String>>();
            dispatchers.add(List.of("DISPATCHER", "JOBS", "MISSES", "QUEUED", "START p50 µs", "p99 µs", "max µs"));
            for (NodeStatus.DispatcherEntry dispatcher : status.dispatchers()) {
                dispatchers.add(List.of(Integer.toString(dispatcher.id()), Long.toString(dispatcher.jobsRun()),
                        Long.toString(dispatcher.deadlineMisses()), Long.toString(dispatcher.queuedJobs()),
                        micros(dispatcher.p50Ns()), micros(dispatcher.p99Ns()), micros(dispatcher.maxNs())));
            }
            table(out, dispatchers);
        }
        return out.toString().stripTrailing();
    }

    static String format(String nodeId, UpgradeResult result) {
        return String.format(Locale.ROOT, "upgraded %s on %s: %s -> %s (from %s, state schema %d); load %s µs,"
                + " pause %s µs, gap %s µs, total %s µs", result.target(), nodeId, result.oldImplementation(),
                result.newImplementation(), result.source(), result.stateSchemaVersion(), micros(result.loadNs()),
                micros(result.pauseNs()), micros(result.gapNs()), micros(result.totalNs()));
    }

    static String format(MigrationResult result) {
        return String.format(Locale.ROOT, "migrated %s from %s to %s (%s, state schema %d, %d messages held);"
                + " prepare %s µs, quiesce %s µs, transfer %s µs, relocate %s µs, gap %s µs, total %s µs",
                result.target(), result.fromNode(), result.toNode(), result.implementation(),
                result.stateSchemaVersion(), result.heldMessages(), micros(result.prepareNs()),
                micros(result.quiesceNs()), micros(result.transferNs()), micros(result.relocateNs()),
                micros(result.gapNs()), micros(result.totalNs()));
    }

    static String format(ManagementFailure failure) {
        return failure.operation() + " of " + failure.target() + " refused or failed: " + failure.reason() + ": "
                + printable(failure.error());
    }

    /** A peer's text with its control characters written as escapes, so it cannot drive the terminal. */
    private static String printable(String text) {
        var out = new StringBuilder(text.length());
        text.codePoints().forEach(c -> {
            if (Character.isISOControl(c)) {
                out.append(String.format(Locale.ROOT, "\\u%04x", c));
            } else {
                out.appendCodePoint(c);
            }
        });
        return out.toString();
    }

    /** A clock offset: signed, "-" only when not known yet. */
    private static String signedMicros(Long nanos) {
        return nanos == null ? "-" : String.format(Locale.ROOT, "%+.1f", nanos / 1_000.0);
    }

    private static String micros(Long nanos) {
        return nanos == null ? "-" : micros(nanos.longValue());
    }

    private static String micros(long nanos) {
        return nanos < 0 ? "-" : String.format(Locale.ROOT, "%.1f", nanos / 1_000.0);
    }

    private static void table(StringBuilder out, List<List<String>> rows) {
        int columns = rows.getFirst().size();
        int[] widths = new int[columns];
        for (List<String> row : rows) {
            for (int i = 0; i < columns; i++) {
                widths[i] = Math.max(widths[i], row.get(i).length());
            }
        }
        for (List<String> row : rows) {
            var line = new StringBuilder();
            for (int i = 0; i < columns; i++) {
                line.append(row.get(i)).append(" ".repeat(widths[i] - row.get(i).length() + (i < columns - 1 ? 2 : 0)));
            }
            out.append(line.toString().stripTrailing()).append('\n');
        }
    }
}
