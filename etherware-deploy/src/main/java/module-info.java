/** Etherware-RT deployment: a node started from an XML description, run until SIGTERM. */
module io.etherware.deploy {
    requires transitive io.etherware.services;
    requires java.xml;
    requires info.picocli;
    requires jdk.httpserver;

    exports io.etherware.deploy;
    exports io.etherware.deploy.view;

    opens io.etherware.deploy to info.picocli;
}
