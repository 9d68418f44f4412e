package io.etherware.deploy.view;

import java.util.ArrayList;
import java.util.LinkedHashMap;
import java.util.List;
import java.util.Map;
import java.util.Optional;

/**
 * A strict reader of the Prometheus text exposition format 0.0.4, as a scraper parses it, for the
 * tests: every line is a {@code # HELP}, a {@code # TYPE} or a sample; a sample's family must have
 * been typed before it; label values are unescaped. Anything else fails the parse.
 */
final class Exposition {

    /** One sample line. */
    record Sample(String name, Map<String, String> labels, double value) {
    }

    final Map<String, String> types = new LinkedHashMap<>();
    final Map<String, String> helps = new LinkedHashMap<>();
    final List<Sample> samples = new ArrayList<>();

    static Exposition parse(String text) {
        var exposition = new Exposition();
        if (!text.endsWith("\n")) {
            throw new IllegalArgumentException("the exposition must end with a line feed");
        }
        int number = 0;
        for (String line : text.split("\n")) {
            number++;
            try {
                exposition.line(line);
            } catch (RuntimeException e) {
                throw new IllegalArgumentException("line " + number + " '" + line + "': " + e.getMessage(), e);
            }
        }
        return exposition;
    }

    private void line(String line) {
        if (line.startsWith("# HELP ")) {
            String[] parts = line.substring(7).split(" ", 2);
            name(parts[0]);
            helps.put(parts[0], parts.length > 1 ? parts[1] : "");
            return;
        }
        if (line.startsWith("# TYPE ")) {
            String[] parts = line.substring(7).split(" ");
            name(parts[0]);
            if (parts.length != 2 || !List.of("counter", "gauge", "summary", "histogram", "untyped")
                    .contains(parts[1])) {
                throw new IllegalArgumentException("bad TYPE");
            }
            if (types.put(parts[0], parts[1]) != null) {
                throw new IllegalArgumentException("family typed twice");
            }
            return;
        }
        if (line.isEmpty() || line.startsWith("#")) {
            throw new IllegalArgumentException("not a line this writer should produce");
        }
        int brace = line.indexOf('{');
        int space;
        String name;
        var labels = new LinkedHashMap<String, String>();
        if (brace < 0) {
            space = line.indexOf(' ');
            name = line.substring(0, space);
        } else {
            name = line.substring(0, brace);
            int i = brace + 1;
            while (line.charAt(i) != '}') {
                int equals = line.indexOf('=', i);
                String label = line.substring(i, equals);
                if (!label.matches("[a-zA-Z_][a-zA-Z0-9_]*")) {
                    throw new IllegalArgumentException("bad label name " + label);
                }
                if (line.charAt(equals + 1) != '"') {
                    throw new IllegalArgumentException("label value not quoted");
                }
                var value = new StringBuilder();
                int k = equals + 2;
                for (; line.charAt(k) != '"'; k++) {
                    char c = line.charAt(k);
                    if (c == '\\') {
                        char next = line.charAt(++k);
                        switch (next) {
                            case '\\' -> value.append('\\');
                            case '"' -> value.append('"');
                            case 'n' -> value.append('\n');
                            default -> throw new IllegalArgumentException("bad escape \\" + next);
                        }
                    } else {
                        value.append(c);
                    }
                }
                labels.put(label, value.toString());
                i = k + 1;
                if (line.charAt(i) == ',') {
                    i++;
                }
            }
            space = i + 1;
            if (line.charAt(space) != ' ') {
                throw new IllegalArgumentException("no space before the value");
            }
        }
        name(name);
        String family = types.containsKey(name) ? name : name.replaceAll("_(sum|count|bucket)$", "");
        if (!types.containsKey(family)) {
            throw new IllegalArgumentException("sample of untyped family " + name);
        }
        String value = line.substring(space + 1);
        double parsed = switch (value) {
            case "NaN" -> Double.NaN;
            case "+Inf" -> Double.POSITIVE_INFINITY;
            case "-Inf" -> Double.NEGATIVE_INFINITY;
            default -> Double.parseDouble(value);
        };
        samples.add(new Sample(name, Map.copyOf(labels), parsed));
    }

    private static void name(String name) {
        if (!name.matches("[a-zA-Z_:][a-zA-Z0-9_:]*")) {
            throw new IllegalArgumentException("bad metric name " + name);
        }
    }

    /** The one sample of {@code name} whose labels include {@code labels}, if any. */
    Optional<Sample> find(String name, Map<String, String> labels) {
        List<Sample> found = samples.stream().filter(s -> s.name().equals(name)
                && s.labels().entrySet().containsAll(labels.entrySet())).toList();
        if (found.size() > 1) {
            throw new IllegalStateException(found.size() + " samples of " + name + " match " + labels);
        }
        return found.stream().findFirst();
    }

    double value(String name, Map<String, String> labels) {
        return find(name, labels).orElseThrow(() -> new AssertionError("no sample " + name + labels + " in "
                + samples)).value();
    }
}
