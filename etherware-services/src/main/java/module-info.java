/** Etherware services: Notifier, NetworkMessenger, NetworkTime, runtime upgrade and migration, recording. */
module io.etherware.services {
    requires transitive io.etherware.core;
    requires transitive io.etherware.rt;

    exports io.etherware.services.management;
    exports io.etherware.services.network;
    exports io.etherware.services.notifier;
    exports io.etherware.services.recording;
    exports io.etherware.services.status;
    exports io.etherware.services.time;
}
