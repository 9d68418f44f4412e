package io.etherware.deploy.view;

import io.etherware.deploy.StatusJson;
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

    /** A {@link NodeStatus} as a JSON object: the control tool's {@code --json}, one writer for both. */
    static String status(NodeStatus status) {
        return StatusJson.format(status);
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

    /** Appends {@code text} as a JSON string ({@link StatusJson#string}). */
    static void string(StringBuilder out, String text) {
        out.append(StatusJson.string(text));
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
