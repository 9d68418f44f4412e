/** Etherware-RT: QoS-driven hierarchical scheduling at real OS priorities. */
module io.etherware.rt {
    requires transitive io.etherware.core;
    requires HdrHistogram;
}
