package io.etherware.rt.scheduling;

import static org.junit.jupiter.api.Assertions.assertEquals;
import static org.junit.jupiter.api.Assertions.assertThrows;
import static org.junit.jupiter.api.Assertions.assertTrue;

import io.etherware.rt.platform.ThreadPolicy;
import org.junit.jupiter.api.Test;

class RealtimeSchedulerConfigTest {

    @Test
    void shouldMirrorTableIIAndAlgorithmOneWhenDefault() {
        var config = RealtimeSchedulerConfig.defaults();
        assertEquals("[0:SCHED_OTHER, 1:SCHED_FIFO/80, 2:SCHED_FIFO/70, 3:SCHED_FIFO/60]",
                config.threadSchedulingRule().toString());
        assertEquals("criticality-deadline", config.placementRule().name());
        assertEquals(AdmissionMode.WARN, config.admissionMode());
        assertTrue(config.priorityInheritance());
    }

    @Test
    void shouldNameBothSidesWhenPlacementNeedsMoreDispatchersThanTheRuleHas() {
        var error = assertThrows(IllegalArgumentException.class, () -> RealtimeSchedulerConfig.builder()
                .threadSchedulingRule(ThreadSchedulingRule.nonRealtime(2)).build());
        assertTrue(error.getMessage().contains("placementRule=criticality-deadline"), error.getMessage());
        assertTrue(error.getMessage().contains("has 2"), error.getMessage());
    }

    @Test
    void shouldNameTheDispatcherWhenARealtimePriorityIsOutOfRange() {
        var error = assertThrows(IllegalArgumentException.class, () -> ThreadSchedulingRule.of(
                DispatcherSpec.nonRealtime(), new DispatcherSpec(ThreadPolicy.fifo(100),
                        io.etherware.rt.platform.CpuSet.inherit())));
        assertEquals("dispatchers[1].priority=100 must be in 1..99 for SCHED_FIFO", error.getMessage());
        assertThrows(IllegalArgumentException.class, () -> ThreadSchedulingRule.of(DispatcherSpec.fifo(0)));
        assertThrows(IllegalArgumentException.class, () -> ThreadSchedulingRule.nonRealtime(0));
    }

    @Test
    void shouldRejectANameThatCannotNameThreads() {
        var error = assertThrows(IllegalArgumentException.class,
                () -> RealtimeSchedulerConfig.builder().name("two words").build());
        assertTrue(error.getMessage().startsWith("name='two words'"), error.getMessage());
    }

    @Test
    void shouldKeepStructureAndDropPrioritiesWhenWithoutRealtime() {
        var rule = ThreadSchedulingRule.tableII().withoutRealtime();
        assertEquals(4, rule.size());
        assertEquals(ThreadPolicy.NON_REALTIME, rule.dispatcher(1).policy());
        assertEquals(0, rule.rank(1));
        assertEquals(80, ThreadSchedulingRule.tableII().rank(1));
    }
}
