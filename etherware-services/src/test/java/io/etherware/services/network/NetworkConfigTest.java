package io.etherware.services.network;

import static org.junit.jupiter.api.Assertions.assertEquals;
import static org.junit.jupiter.api.Assertions.assertSame;
import static org.junit.jupiter.api.Assertions.assertThrows;
import static org.junit.jupiter.api.Assertions.assertTrue;

import io.etherware.core.codec.MessageCodec;
import io.etherware.core.kernel.EtherwareNode;
import java.time.Duration;
import org.junit.jupiter.api.Test;

/** Misconfiguration fails at build time naming the field ({@link NetworkConfigIT}: at start, on real sockets). */
class NetworkConfigTest {

    private static String errorOf(NetworkConfig.Builder builder) {
        return assertThrows(IllegalArgumentException.class, builder::build).getMessage();
    }

    @Test
    void shouldNameTheFieldAndValueOfABadSetting() {
        assertTrue(errorOf(NetworkConfig.builder().maxFrameBytes(100)).startsWith("maxFrameBytes=100"));
        assertTrue(errorOf(NetworkConfig.builder().queueCapacity(0)).startsWith("queueCapacity=0"));
        assertTrue(errorOf(NetworkConfig.builder().windowMessages(1)).startsWith("windowMessages=1"));
        String heartbeat = errorOf(NetworkConfig.builder().heartbeatInterval(Duration.ofSeconds(2))
                .heartbeatTimeout(Duration.ofSeconds(3)));
        assertTrue(heartbeat.startsWith("heartbeatTimeoutNs=3000000000") && heartbeat.contains("twice"), heartbeat);
        assertTrue(errorOf(NetworkConfig.builder().reconnectBackoff(Duration.ofSeconds(1), Duration.ofMillis(10), 0.2))
                .startsWith("reconnectMaxBackoffNs=10000000"));
        assertTrue(errorOf(NetworkConfig.builder().reconnectBackoff(Duration.ofMillis(10), Duration.ofSeconds(1), 1.0))
                .startsWith("reconnectJitter=1.0"));
        assertTrue(errorOf(NetworkConfig.builder().timeProbes(Duration.ofSeconds(1), 100)).startsWith("timeProbeBurst=100"));
        assertTrue(errorOf(NetworkConfig.builder().maxHops(-1)).startsWith("maxHops=-1"));
    }

    @Test
    void shouldFitTheDefaultCodecToTheFrameLimitOverTheNodesContentsTypes() {
        NetworkConfig config = NetworkConfig.builder().maxFrameBytes(64 * 1024).build();
        var node = EtherwareNode.builder().nodeId("fit").build();
        var codec = config.codecFor(node);
        assertTrue(codec.maxDocumentBytes() < config.maxFrameBytes(), () -> "document limit " + codec.maxDocumentBytes());
        assertSame(node.contentsTypes(), codec.contentsTypes());
        assertTrue(codec.contentsTypes().names().contains("undeliverable"), () -> codec.contentsTypes().names().toString());
        assertEquals(NetworkConfig.DEFAULT_MAX_FRAME_BYTES, NetworkConfig.builder().build().maxFrameBytes());
    }

    @Test
    void shouldRefuseACodecWhoseDocumentsAreSmallerThanPeersRequire() {
        var small = MessageCodec.builder().maxDocumentBytes(NetworkConfig.MIN_CODEC_DOCUMENT_BYTES - 1).build();
        assertTrue(errorOf(NetworkConfig.builder().codec(small)).startsWith("codec.maxDocumentBytes()=1023 must be at"
                + " least 1024"));
        var enough = MessageCodec.builder().maxDocumentBytes(NetworkConfig.MIN_CODEC_DOCUMENT_BYTES).build();
        assertSame(enough, NetworkConfig.builder().codec(enough).build().codec());
    }
}
