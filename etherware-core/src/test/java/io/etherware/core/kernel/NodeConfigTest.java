package io.etherware.core.kernel;

import static org.junit.jupiter.api.Assertions.assertEquals;
import static org.junit.jupiter.api.Assertions.assertThrows;
import static org.junit.jupiter.api.Assertions.assertTrue;

import io.etherware.core.message.Profile;
import io.etherware.core.time.NodeClock;
import java.time.Duration;
import org.junit.jupiter.api.Test;

class NodeConfigTest {

    @Test
    void shouldUseTheDocumentedDefaultsWhenNothingIsSet() {
        NodeConfig config = NodeConfig.builder().build();
        assertEquals("node", config.nodeId());
        assertEquals("fifo", config.scheduler().get().name());
        assertEquals(NodeClock.system(), config.clock());
        assertEquals(SupervisionPolicy.DEFAULT, config.supervision());
        assertEquals(Escalation.RESET_ALL, config.escalation());
        assertEquals(1_000_000_000L, config.defaultRequestTimeoutNs());
        assertEquals(1_000_000_000L, config.drainTimeoutNs());
    }

    @Test
    void shouldNameTheFieldAndValueWhenTheNodeIdIsInvalid() {
        var error = assertThrows(IllegalArgumentException.class, () -> EtherwareNode.builder().nodeId("plant 1").build());
        assertTrue(error.getMessage().startsWith("nodeId='plant 1' must match"), error.getMessage());
    }

    @Test
    void shouldNameTheFieldAndValueWhenATimeoutIsNotPositive() {
        var error = assertThrows(IllegalArgumentException.class,
                () -> NodeConfig.builder().defaultRequestTimeout(Duration.ZERO).build());
        assertTrue(error.getMessage().startsWith("defaultRequestTimeoutNs=0 must be > 0"), error.getMessage());
        var drain = assertThrows(IllegalArgumentException.class,
                () -> NodeConfig.builder().drainTimeout(Duration.ofMillis(-1)).build());
        assertTrue(drain.getMessage().startsWith("drainTimeoutNs=-1000000 must be >= 0"), drain.getMessage());
    }

    @Test
    void shouldNameTheFieldWhenARequiredPartIsNull() {
        var error = assertThrows(NullPointerException.class, () -> NodeConfig.builder().scheduler(null).build());
        assertTrue(error.getMessage().startsWith("scheduler=null"), error.getMessage());
    }

    @Test
    void shouldRejectAnIntensityOutOfRange() {
        var error = assertThrows(IllegalArgumentException.class,
                () -> SupervisionPolicy.fromSnapshot(-1, Duration.ofSeconds(1)));
        assertTrue(error.getMessage().startsWith("maxRestarts=-1"), error.getMessage());
        var window = assertThrows(IllegalArgumentException.class, () -> SupervisionPolicy.fresh(1, Duration.ZERO));
        assertTrue(window.getMessage().startsWith("windowNs=0"), window.getMessage());
    }

    @Test
    void shouldRefuseADuplicateProfileWhenAddingAComponent() {
        try (var node = EtherwareNode.builder().nodeId("dup").build()) {
            node.add(Profile.of("x"), () -> (m, c) -> { });
            var error = assertThrows(IllegalArgumentException.class,
                    () -> node.add(Profile.of("x"), () -> (m, c) -> { }));
            assertTrue(error.getMessage().contains("profile 'x' is already registered"), error.getMessage());
        }
    }
}
