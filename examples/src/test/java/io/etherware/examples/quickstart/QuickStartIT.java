package io.etherware.examples.quickstart;

import static org.junit.jupiter.api.Assertions.assertTrue;

import java.time.Duration;
import org.junit.jupiter.api.Test;

/** The README's complete program runs: the Notifier accepts the subscription and the room warms. */
class QuickStartIT {

    @Test
    void shouldWarmTheRoomTowardItsSetPointAcrossTwoNodes() throws Exception {
        QuickStart.Result result = QuickStart.run(Duration.ofSeconds(2));

        // 20 periods of 100 ms: at least a few closed cycles even on a loaded machine.
        assertTrue(result.cycles() >= 3, () -> result.cycles() + " control cycles");
        // From 15 °C with full heat the room gains about 0.4 °C per cycle, never past the set point by much.
        assertTrue(result.celsius() > 15.5 && result.celsius() < 22.0, () -> result.celsius() + " °C");
    }
}
