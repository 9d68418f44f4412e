/** Etherware-RT deployment: a node started from an XML description, run until SIGTERM. */
module io.etherware.deploy {
    requires transitive io.etherware.services;
    requires java.xml;
    requires info.picocli;

    exports io.etherware.deploy;

    opens io.etherware.deploy to info.picocli;
}
