package io.etherware.services.management;

import static org.junit.jupiter.api.Assertions.assertEquals;
import static org.junit.jupiter.api.Assertions.assertTrue;

import io.etherware.services.network.NetworkConfig;
import java.time.Duration;
import org.junit.jupiter.api.Test;

/** How long a migration's source may look for its target having died, against the network's grace. */
class ManagementConfigTest {

    @Test
    void shouldWatchForADeadTargetForTwoStepsAndTheFirstMessageWait() {
        assertEquals(Duration.ofSeconds(5).toNanos(), ManagementConfig.defaults().targetWatchNs());
        ManagementConfig config = ManagementConfig.builder().migrationStepTimeout(Duration.ofSeconds(3))
                .handoverWait(Duration.ofSeconds(7)).firstMessageWait(Duration.ofMillis(500)).build();
        assertEquals(Duration.ofMillis(6_500).toNanos(), config.targetWatchNs());
    }

    @Test
    void shouldSaturateRatherThanOverflow() {
        ManagementConfig config = ManagementConfig.builder().migrationStepTimeout(Duration.ofDays(60_000))
                .handoverWait(Duration.ofDays(70_000)).build();
        assertEquals(Long.MAX_VALUE, config.targetWatchNs());
    }

    @Test
    void shouldLeaveTheDefaultGraceOfTheNetworkAboveTheDefaultWatch() {
        // The default configurations work together: a source still sees its dead target when it looks.
        assertTrue(NetworkConfig.builder().build().peerDownGraceNs() > ManagementConfig.defaults().targetWatchNs());
    }
}
