package io.etherware.examples.scenario;

import java.util.Objects;

/**
 * Something that happened during a scenario run and is marked in its CSV and plots: a stress
 * activation starting or ending, the pendulum falling, an upgrade, a migration. Immutable.
 *
 * @param timeNs when, on the node's monotonic clock
 * @param kind what kind of event, for styling and counting
 * @param label what the CSV and the plot say, e.g. {@code stress 2 start}
 */
public record ScenarioEvent(long timeNs, Kind kind, String label) {

    /** The kinds of events the scenarios mark. */
    public enum Kind {
        /** A stress computation began. */
        STRESS_START,
        /** A stress computation ended. */
        STRESS_END,
        /** |θ2| passed the fall threshold for the first time. */
        FELL,
        /** A management request replaced a component's logic (or tried to). */
        UPGRADE,
        /** A management request moved a component to another node (or tried to). */
        MIGRATION,
        /** Anything else worth a mark. */
        NOTE
    }

    public ScenarioEvent {
        Objects.requireNonNull(kind, "kind");
        Objects.requireNonNull(label, "label");
        if (label.isBlank() || label.indexOf(',') >= 0 || label.indexOf(';') >= 0 || label.indexOf('\n') >= 0) {
            throw new IllegalArgumentException("label='" + label
                    + "' must be non-blank and free of ',', ';' and line breaks (it goes into a CSV cell)");
        }
    }
}
