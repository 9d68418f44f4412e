/**
 * Etherware-RT: QoS-driven hierarchical scheduling at real OS priorities (paper Section IV-B): the
 * Dispatching Module with its Job Placement and Thread Scheduling Rules, OS thread priorities,
 * affinity and memory locking through the FFM API, deadline accounting and admission control.
 *
 * <p>Run with {@code --enable-native-access=io.etherware.rt} (or {@code ALL-UNNAMED} on the class
 * path) so the OS calls work without the JVM's restricted-method warning.
 */
module io.etherware.rt {
    requires transitive io.etherware.core;
    // HdrHistogram 2.2.2 declares no module name (no module-info, no Automatic-Module-Name): its name
    // is derived from the jar. Not transitive: the API hands out LatencySnapshot, never its types.
    requires HdrHistogram;
    requires jdk.jfr;

    exports io.etherware.rt.platform;
    exports io.etherware.rt.scheduling;
    exports io.etherware.rt.stats;
}
