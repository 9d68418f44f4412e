package io.etherware.core.message;

import static org.junit.jupiter.api.Assertions.assertEquals;
import static org.junit.jupiter.api.Assertions.assertFalse;
import static org.junit.jupiter.api.Assertions.assertNull;
import static org.junit.jupiter.api.Assertions.assertThrows;
import static org.junit.jupiter.api.Assertions.assertTrue;

import org.junit.jupiter.api.Test;

class OriginTest {

    private final Message made = new Message(Profile.of("sensor"), Profile.of("controller"), 1, QoS.NONE,
            new Text("x"), new MessageId("a", 7), null);

    @Test
    void shouldHaveNoOriginWhenMadeOnThisNode() {
        assertNull(made.origin());
        assertTrue(made.isLocal());
    }

    @Test
    void shouldKeepTheOriginWhenTheProfileOrTimeStampChanges() {
        Origin origin = new Origin("a", "b", 1, true);
        Message received = made.withOrigin(origin);
        assertFalse(received.isLocal());
        assertEquals(origin, received.withProfile(Profile.of("other")).origin());
        assertEquals(origin, received.withTimeStamp(99).origin());
    }

    @Test
    void shouldRefuseADirectOriginThroughAnotherNode() {
        var e = assertThrows(IllegalArgumentException.class, () -> new Origin("a", "b", 0, true));
        assertTrue(e.getMessage().contains("hops=0"), e.getMessage());
        assertTrue(Origin.direct("a", false).isDirect());
        assertThrows(IllegalArgumentException.class, () -> new Origin("a", "b", -1, true));
    }
}
