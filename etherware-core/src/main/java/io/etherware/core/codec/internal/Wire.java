package io.etherware.core.codec.internal;

/**
 * The element and attribute names of the wire format, in one place; see {@code WIRE-FORMAT.md}
 * and {@code etherware-message.xsd}, which must change with them.
 */
final class Wire {

    /** The wire format version this codec writes and the only one it reads. */
    static final String VERSION_1 = "1";

    static final String MESSAGE = "message";
    static final String VERSION = "version";
    static final String PROFILE = "profile";
    static final String SENDER = "sender";
    static final String TIME_STAMP = "timeStamp";
    static final String QOS = "qos";
    static final String CRITICALITY = "criticality";
    static final String PERIOD_NS = "periodNs";
    static final String DEADLINE_NS = "deadlineNs";
    static final String WCET_NS = "wcetNs";
    static final String MESSAGE_ID = "messageId";
    static final String CORRELATION_ID = "correlationId";
    static final String CONTENTS = "contents";

    /** The attribute naming a contents element's registered type. */
    static final String TYPE = "type";
    /** The element of each list entry. */
    static final String ITEM = "item";

    private Wire() {
    }
}
