package io.etherware.examples.migrate;

import static org.junit.jupiter.api.Assertions.assertEquals;
import static org.junit.jupiter.api.Assertions.assertThrows;
import static org.junit.jupiter.api.Assertions.assertTrue;

import io.etherware.core.codec.MessageCodec;
import io.etherware.core.message.Message;
import io.etherware.core.message.MessageId;
import io.etherware.core.message.QoS;
import io.etherware.pendulum.components.ControlCycle;
import java.nio.file.Path;
import org.junit.jupiter.api.Test;

/** The migration scenario's settings, its cycle report on the wire and its controller's configuration. */
class MigrateConfigTest {

    private static final Path OUT = Path.of("target", "migrate-config-test");

    @Test
    void shouldMigrateAtFortySecondsOfAMinuteAndTwoThirdsIntoAShorterRun() {
        assertEquals(MigrateConfig.DEFAULT_MIGRATE_AT_NS, MigrateConfig.of(60_000_000_000L, 15_000_000L, OUT).migrateAtNs());
        assertEquals(8_000_000_000L, MigrateConfig.of(12_000_000_000L, 15_000_000L, OUT).migrateAtNs());
    }

    @Test
    void shouldLeaveTwoSecondsOnNode1ByDefaultInTheShortestRuns() {
        assertEquals(2_000_000_000L, MigrateConfig.of(MigrateConfig.MIN_DURATION_NS, 15_000_000L, OUT).migrateAtNs());
        assertEquals(3_000_000_000L, MigrateConfig.of(5_000_000_000L, 15_000_000L, OUT).migrateAtNs());
    }

    @Test
    void shouldNameTheFieldWhenTheMigrationLeavesTooLittleTimeOnANode() {
        var error = assertThrows(IllegalArgumentException.class,
                () -> MigrateConfig.of(10_000_000_000L, 15_000_000L, OUT).withMigrateAtNs(9_000_000_000L));
        assertTrue(error.getMessage().startsWith("migrateAtNs=9000000000"), error.getMessage());
    }

    @Test
    void shouldCarryACycleAcrossTheWireExactlyIncludingAMissedCyclesNaNs() {
        var codec = new MessageCodec(CycleReport.register(new io.etherware.core.message.ContentsTypes()));
        var missed = new ControlCycle(7, 100, 110, 120, ControlCycle.Outcome.values()[1], Double.NaN, Double.NaN,
                Double.NaN, Double.NaN, -1, Double.NaN, 1);
        for (ControlCycle cycle : new ControlCycle[] {missed, new ControlCycle(8, 200, 210, 220,
                ControlCycle.Outcome.COMMANDED, 0.01, -0.02, 0.3, -0.4, 1234, 0.05, 2)}) {
            var message = new Message(CycleReport.RECORDER, CycleReport.RECORDER, 1, QoS.NONE, new CycleReport(cycle),
                    new MessageId("node-2", 1), null);
            assertEquals(cycle, codec.decode(codec.encode(message)).contentsAs(CycleReport.class).cycle());
        }
    }

    @Test
    void shouldRefuseAControllerConfigurationWithoutAListener() {
        var error = assertThrows(IllegalArgumentException.class, () -> new ListenedController("gains=v1"));
        assertTrue(error.getMessage().contains("listener=<name>"), error.getMessage());
    }
}
