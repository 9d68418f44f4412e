package io.etherware.examples.bench;

/** The load a row is measured under. */
enum Condition {
    /** Nothing else running in the JVM (the machine may still be shared). */
    IDLE("idle", "idle"),
    /** One ordinary spinning thread per core. */
    LOADED("loaded", "every core loaded"),
    /** A LOW-criticality message flood on top of every core loaded. */
    FLOOD("flood", "LOW flood + every core loaded");

    private final String id;
    private final String label;

    Condition(String id, String label) {
        this.id = id;
        this.label = label;
    }

    String id() {
        return id;
    }

    String label() {
        return label;
    }
}
