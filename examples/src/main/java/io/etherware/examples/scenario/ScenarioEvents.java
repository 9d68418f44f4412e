package io.etherware.examples.scenario;

import java.util.ArrayList;
import java.util.Comparator;
import java.util.List;
import java.util.concurrent.ConcurrentLinkedQueue;

/**
 * The events of one run, collected from whichever thread sees them (a dispatcher, the probe).
 *
 * <p>Thread-safe and lock-free: {@link #add} appends to a concurrent queue; it allocates one small
 * record, which is harmless at the rate of scenario events (a few per second at most).
 */
public final class ScenarioEvents {

    private final ConcurrentLinkedQueue<ScenarioEvent> events = new ConcurrentLinkedQueue<>();

    /** Records an event at {@code timeNs} on the node's monotonic clock. */
    public void add(long timeNs, ScenarioEvent.Kind kind, String label) {
        events.add(new ScenarioEvent(timeNs, kind, label));
    }

    /** The events so far, in time order. */
    public List<ScenarioEvent> snapshot() {
        List<ScenarioEvent> copy = new ArrayList<>(events);
        copy.sort(Comparator.comparingLong(ScenarioEvent::timeNs));
        return copy;
    }
}
