package io.etherware.deploy.view;

import static org.junit.jupiter.api.Assertions.assertFalse;
import static org.junit.jupiter.api.Assertions.assertThrows;
import static org.junit.jupiter.api.Assertions.assertTrue;

import java.net.InetSocketAddress;
import org.junit.jupiter.api.Test;

class ViewConfigTest {

    @Test
    void shouldRefuseAnAddressBeyondLoopbackUnlessAllowed() {
        var any = new InetSocketAddress("0.0.0.0", 8080);

        var e = assertThrows(IllegalArgumentException.class, () -> new ViewConfig(any, false));

        assertTrue(e.getMessage().contains("0.0.0.0:8080") && e.getMessage().contains("allowRemote"),
                e.getMessage());
        assertTrue(new ViewConfig(any, true).allowRemote());
        assertFalse(ViewConfig.loopback(0).allowRemote());
    }

    @Test
    void shouldTakeOnlyLoopbackNamesInTheHostHeaderOnLoopback() {
        for (String host : new String[] {"127.0.0.1:8080", "localhost:8080", "LOCALHOST", "[::1]:8080", "127.0.0.2",
                null}) {
            assertTrue(NodeView.loopbackHost(host), host);
        }
        for (String host : new String[] {"evil.example:8080", "127.0.0.1.evil.example", "10.0.0.1", "[::2]:80"}) {
            assertFalse(NodeView.loopbackHost(host), host);
        }
    }
}
