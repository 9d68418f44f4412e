package io.etherware.examples.netstress;

import io.etherware.examples.scenario.ScenarioEvent;
import java.io.PrintWriter;
import java.util.ArrayList;
import java.util.List;
import java.util.Objects;

/**
 * What node 2 of the networked stress experiment reports when its run ends, as lines on its
 * standard output after {@code READY}: {@code EVENT <timeNs> <kind> <label>} per stress task mark,
 * {@code MISSES <n>} (its scheduler's count, {@link #NOT_COUNTED} on the original Etherware, whose
 * FIFO dispatcher counts none) and {@code NOTE <text>} per note line. Immutable.
 *
 * @param misses node 2's scheduler-counted deadline misses, or {@link #NOT_COUNTED}
 * @param events node 2's stress task marks, on the host's monotonic clock
 * @param notes  lines for the run's notes
 */
record Results(long misses, List<ScenarioEvent> events, List<String> notes) {

    /** No count: the scheduler does not count deadline misses. */
    static final long NOT_COUNTED = -1;
    /** Node 2 reported nothing (it died or never got to the end). */
    static final Results NONE = new Results(NOT_COUNTED, List.of(), List.of("  node 2 reported no results"));

    private static final String EVENT = "EVENT";
    private static final String MISSES = "MISSES";
    private static final String NOTE = "NOTE";

    Results {
        events = List.copyOf(events);
        notes = List.copyOf(notes);
    }

    /** Stress activations node 2 started. */
    long activations() {
        return events.stream().filter(e -> e.kind() == ScenarioEvent.Kind.STRESS_START).count();
    }

    /**
     * The results in {@code lines}; lines of another form (a stray print) are kept as notes.
     * Without a {@code MISSES} line the node did not finish: {@link #NONE} with those notes.
     */
    static Results parse(List<String> lines) {
        long misses = NOT_COUNTED;
        boolean finished = false;
        List<ScenarioEvent> events = new ArrayList<>();
        List<String> notes = new ArrayList<>();
        for (String line : lines) {
            String[] words = line.split(" ", 4);
            try {
                if (words[0].equals(EVENT) && words.length == 4) {
                    events.add(new ScenarioEvent(Long.parseLong(words[1]), ScenarioEvent.Kind.valueOf(words[2]),
                            words[3]));
                    continue;
                } else if (words[0].equals(MISSES) && words.length == 2) {
                    misses = Long.parseLong(words[1]);
                    finished = true;
                    continue;
                } else if (line.startsWith(NOTE + " ")) {
                    notes.add(line.substring(NOTE.length() + 1));
                    continue;
                }
            } catch (IllegalArgumentException e) {
                // kept as a note below
            }
            notes.add("  node 2 printed: " + line);
        }
        if (!finished) {
            List<String> all = new ArrayList<>(NONE.notes());
            all.addAll(notes);
            return new Results(NOT_COUNTED, events, all);
        }
        return new Results(misses, events, notes);
    }

    /** Writes the lines {@link #parse} reads. Used by one thread. */
    static final class Writer {
        private final PrintWriter out;

        Writer(PrintWriter out) {
            this.out = Objects.requireNonNull(out, "out");
        }

        void event(ScenarioEvent event) {
            out.println(EVENT + " " + event.timeNs() + " " + event.kind().name() + " " + event.label());
        }

        void misses(long count) {
            out.println(MISSES + " " + count);
        }

        void note(String text) {
            out.println(NOTE + " " + text.replace('\n', ' '));
        }
    }
}
