package example.counter;

import java.util.List;
import java.util.Map;
import java.util.concurrent.ConcurrentHashMap;
import java.util.concurrent.CopyOnWriteArrayList;

/**
 * Where the test counters write what they handled, found by name: a logic made by the management
 * service gets the journal's name as its configuration string.
 */
public final class Journal {

    /** One handled message: which logic handled it, its sequence, and the count after it. */
    public record Entry(String version, long sequence, long count) {
    }

    private static final Map<String, Journal> BY_NAME = new ConcurrentHashMap<>();

    private final List<Entry> entries = new CopyOnWriteArrayList<>();

    private Journal() {
    }

    /** A new, empty journal under {@code name}. */
    public static Journal create(String name) {
        var journal = new Journal();
        BY_NAME.put(name, journal);
        return journal;
    }

    /** The journal named {@code name}. */
    public static Journal named(String name) {
        Journal journal = BY_NAME.get(name);
        if (journal == null) {
            throw new IllegalArgumentException("no journal named '" + name + "'");
        }
        return journal;
    }

    public void add(String version, long sequence, long count) {
        entries.add(new Entry(version, sequence, count));
    }

    public List<Entry> entries() {
        return entries;
    }

    public int size() {
        return entries.size();
    }
}
