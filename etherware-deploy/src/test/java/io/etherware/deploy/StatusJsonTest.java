package io.etherware.deploy;

import static org.junit.jupiter.api.Assertions.assertEquals;

import io.etherware.services.status.NodeStatus;
import java.util.List;
import org.junit.jupiter.api.Test;

class StatusJsonTest {

    @Test
    void shouldEscapeQuotesBackslashesAndControlCharacters() {
        assertEquals("\"a\\\"b\\\\c\\nd\\u0001\\u2028\"", StatusJson.string("a\"b\\c\nd\u0001\u2028"));
        assertEquals("null", StatusJson.string(null));
    }

    @Test
    void shouldWriteUnknownClockOffsetsAsNull() {
        var status = new NodeStatus("n", 1, "fifo", List.of(), List.of(),
                List.of(new NodeStatus.PeerEntry("p", false, "", 0, 0, null, null)),
                new NodeStatus.Counters(0, 0, 0, 0, 0, 0));

        assertEquals("{\"nodeId\":\"n\",\"epochNs\":1,\"scheduler\":\"fifo\",\"counters\":{\"handled\":0,\"failed\":0,"
                + "\"restarts\":0,\"undeliverable\":0,\"requestTimeouts\":0,\"deadlineMisses\":0},\"components\":[],"
                + "\"dispatchers\":[],\"peers\":[{\"nodeId\":\"p\",\"connected\":false,\"remote\":\"\",\"queued\":0,"
                + "\"profiles\":0,\"clockOffsetNs\":null,\"roundTripNs\":null}]}", StatusJson.format(status));
    }
}
