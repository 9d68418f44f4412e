package io.etherware.rt.scheduling;

import static org.junit.jupiter.api.Assertions.assertEquals;
import static org.junit.jupiter.api.Assertions.assertFalse;
import static org.junit.jupiter.api.Assertions.assertThrows;
import static org.junit.jupiter.api.Assertions.assertTrue;

import io.etherware.core.message.Criticality;
import io.etherware.core.message.Profile;
import io.etherware.core.message.QoS;
import org.junit.jupiter.api.Test;

class AdmissionControlTest {

    private static final long MS = 1_000_000L;

    private static AdmissionControl admission(JobPlacementRule rule, AdmissionMode mode) {
        return new RealtimeScheduler(RealtimeSchedulerConfig.builder().placementRule(rule).admissionMode(mode).build())
                .admission();
    }

    @Test
    void shouldPutAStreamOnTheDispatcherOfItsCriticalityAndSumUtilization() {
        var admission = admission(new CriticalityDeadlinePlacement(), AdmissionMode.REJECT);
        DispatcherLoad first = admission.declare(PeriodicStream.of(Profile.of("controller"), Criticality.HIGH,
                15 * MS, 3 * MS));
        DispatcherLoad second = admission.declare(PeriodicStream.of(Profile.of("logger"), Criticality.HIGH,
                100 * MS, 50 * MS));
        assertEquals(1, first.dispatcherId());
        assertEquals(0.2, first.utilization(), 1e-9);
        assertEquals(0.7, second.utilization(), 1e-9);
        assertEquals(QueuePolicy.EARLIEST_DEADLINE_FIRST, second.policy());
        assertTrue(second.isSchedulable());
        assertEquals(0.0, admission.loads().get(3).utilization());
        assertEquals(2, admission.loads().get(1).streams());
    }

    @Test
    void shouldRejectNamingDispatcherUtilizationAndBoundWhenEdfWouldExceedOne() {
        var admission = admission(new CriticalityDeadlinePlacement(), AdmissionMode.REJECT);
        admission.declare(PeriodicStream.of(Profile.of("a"), Criticality.MIDDLE, 10 * MS, 6 * MS));
        var error = assertThrows(AdmissionRejectedException.class, () -> admission.declare(
                PeriodicStream.of(Profile.of("b"), Criticality.MIDDLE, 10 * MS, 5 * MS)));
        assertEquals(2, error.loadWithStream().dispatcherId());
        assertTrue(error.getMessage().contains("dispatcher 2 (EARLIEST_DEADLINE_FIRST): U=1.100 > bound 1.000"),
                error.getMessage());
        assertEquals(1, admission.loads().get(2).streams(), "the rejected stream was not added");
    }

    @Test
    void shouldApplyTheLiuLaylandBoundWhenRateMonotonic() {
        var admission = admission(new RateMonotonicPlacement(), AdmissionMode.REJECT);
        admission.declare(PeriodicStream.of(Profile.of("a"), Criticality.HIGH, 10 * MS, 4 * MS));
        // 0.4 + 0.45 = 0.85 > 2 (sqrt 2 - 1) = 0.828, though an EDF dispatcher would take it.
        var error = assertThrows(AdmissionRejectedException.class, () -> admission.declare(
                PeriodicStream.of(Profile.of("b"), Criticality.HIGH, 20 * MS, 9 * MS)));
        assertTrue(error.getMessage().contains("U=0.850 > bound 0.828 with 2 streams"), error.getMessage());
        DispatcherLoad fits = admission.declare(PeriodicStream.of(Profile.of("b"), Criticality.HIGH, 20 * MS, 8 * MS));
        assertTrue(fits.isSchedulable(), fits.toString());
    }

    @Test
    void shouldAdmitAndReportUnschedulableWhenWarning() {
        var admission = admission(new CriticalityDeadlinePlacement(), AdmissionMode.WARN);
        admission.declare(PeriodicStream.of(Profile.of("a"), Criticality.LOW, 10 * MS, 8 * MS));
        DispatcherLoad load = admission.declare(PeriodicStream.of(Profile.of("b"), Criticality.LOW, 10 * MS, 8 * MS));
        assertFalse(load.isSchedulable());
        assertEquals(1.6, admission.loads().get(3).utilization(), 1e-9);
        assertTrue(admission.withdraw(PeriodicStream.of(Profile.of("b"), Criticality.LOW, 10 * MS, 8 * MS)));
        assertTrue(admission.loads().get(3).isSchedulable());
    }

    @Test
    void shouldNameTheFieldWhenAStreamLacksPeriodOrWcet() {
        var noWcet = assertThrows(IllegalArgumentException.class,
                () -> new PeriodicStream(Profile.of("a"), QoS.periodic(Criticality.HIGH, 10 * MS)));
        assertTrue(noWcet.getMessage().contains("qos.wcetNs=0"), noWcet.getMessage());
        var noPeriod = assertThrows(IllegalArgumentException.class,
                () -> new PeriodicStream(Profile.of("a"), QoS.of(Criticality.HIGH).withWcetNs(MS)));
        assertTrue(noPeriod.getMessage().contains("qos.periodNs=0"), noPeriod.getMessage());
        var tooLong = assertThrows(IllegalArgumentException.class,
                () -> PeriodicStream.of(Profile.of("a"), Criticality.HIGH, 10 * MS, 11 * MS));
        assertTrue(tooLong.getMessage().contains("exceeds its deadlineNs=10000000"), tooLong.getMessage());
    }
}
