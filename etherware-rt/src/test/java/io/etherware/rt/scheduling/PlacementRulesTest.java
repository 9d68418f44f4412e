package io.etherware.rt.scheduling;

import static io.etherware.rt.scheduling.TestJobs.job;
import static org.junit.jupiter.api.Assertions.assertEquals;
import static org.junit.jupiter.api.Assertions.assertThrows;

import io.etherware.core.message.Criticality;
import io.etherware.core.message.QoS;
import org.junit.jupiter.api.Test;

class PlacementRulesTest {

    private static final long NOW_NS = 5_000_000_000L;
    private static final long PERIOD_NS = 15_000_000L;

    // ---- Algorithm 1, case by case ----

    @Test
    void shouldPlaceHighOnDispatcherOneAtNowPlusPeriodWhenCriticalityIsHigh() {
        var rule = new CriticalityDeadlinePlacement();
        assertEquals(new Placement(1, NOW_NS + PERIOD_NS), rule.place(job("a", Criticality.HIGH, PERIOD_NS, 0), NOW_NS));
    }

    @Test
    void shouldPlaceMiddleOnDispatcherTwoAtNowPlusPeriodWhenCriticalityIsMiddle() {
        var rule = new CriticalityDeadlinePlacement();
        assertEquals(new Placement(2, NOW_NS + PERIOD_NS),
                rule.place(job("a", Criticality.MIDDLE, PERIOD_NS, 0), NOW_NS));
    }

    @Test
    void shouldPlaceLowOnDispatcherThreeAtNowPlusPeriodWhenCriticalityIsLow() {
        var rule = new CriticalityDeadlinePlacement();
        assertEquals(new Placement(3, NOW_NS + PERIOD_NS), rule.place(job("a", Criticality.LOW, PERIOD_NS, 0), NOW_NS));
    }

    @Test
    void shouldPlaceOnTheNonRealtimeDispatcherInArrivalOrderWhenMessageHasNoQos() {
        var rule = new CriticalityDeadlinePlacement();
        assertEquals(new Placement(0, NOW_NS), rule.place(job("a", QoS.NONE, 0), NOW_NS));
    }

    @Test
    void shouldUseNowAsKeyWhenCriticalMessageHasNoPeriod() {
        var rule = new CriticalityDeadlinePlacement();
        assertEquals(new Placement(1, NOW_NS), rule.place(job("a", Criticality.HIGH, 0, 0), NOW_NS));
    }

    @Test
    void shouldSaturateInsteadOfWrappingWhenNowPlusPeriodOverflows() {
        var rule = new CriticalityDeadlinePlacement();
        var qos = QoS.periodic(Criticality.LOW, Long.MAX_VALUE - 1);
        assertEquals(new Placement(3, Long.MAX_VALUE), rule.place(job("a", qos, 0), NOW_NS));
    }

    @Test
    void shouldUseEarliestDeadlineWithinRealtimeDispatchersAndFifoOnZeroForAdmission() {
        var rule = new CriticalityDeadlinePlacement();
        assertEquals(4, rule.dispatchersRequired());
        assertEquals(QueuePolicy.FIFO, rule.queuePolicy(0));
        assertEquals(QueuePolicy.EARLIEST_DEADLINE_FIRST, rule.queuePolicy(1));
        assertEquals(QueuePolicy.EARLIEST_DEADLINE_FIRST, rule.queuePolicy(3));
    }

    // ---- rate-monotonic ----

    @Test
    void shouldKeyByPeriodOnDispatcherOneWhenJobIsPeriodic() {
        var rule = new RateMonotonicPlacement();
        assertEquals(new Placement(1, PERIOD_NS), rule.place(job("a", Criticality.LOW, PERIOD_NS, 0), NOW_NS));
        assertEquals(new Placement(1, 2 * PERIOD_NS),
                rule.place(job("a", Criticality.HIGH, 2 * PERIOD_NS, 0), NOW_NS));
        assertEquals(new Placement(0, NOW_NS), rule.place(job("a", Criticality.HIGH, 0, 0), NOW_NS));
        assertEquals(QueuePolicy.RATE_MONOTONIC, rule.queuePolicy(1));
        assertEquals(2, rule.dispatchersRequired());
    }

    @Test
    void shouldSpreadPeriodsOverDispatchersWhenBanded() {
        var rule = RateMonotonicPlacement.banded(10_000_000L, 100_000_000L);
        assertEquals(1, rule.place(job("a", Criticality.LOW, 10_000_000L, 0), NOW_NS).dispatcherId());
        assertEquals(2, rule.place(job("a", Criticality.LOW, 10_000_001L, 0), NOW_NS).dispatcherId());
        assertEquals(2, rule.place(job("a", Criticality.LOW, 100_000_000L, 0), NOW_NS).dispatcherId());
        assertEquals(3, rule.place(job("a", Criticality.LOW, 1_000_000_000L, 0), NOW_NS).dispatcherId());
        assertEquals(4, rule.dispatchersRequired());
        assertThrows(IllegalArgumentException.class, () -> RateMonotonicPlacement.banded(5, 5));
    }

    // ---- EDF ----

    @Test
    void shouldKeyByAbsoluteDeadlineWhenJobHasADeadline() {
        var rule = new EdfPlacement();
        long releaseNs = NOW_NS - 1_000_000L;
        var qos = QoS.of(Criticality.LOW).withDeadlineNs(4_000_000L);
        assertEquals(new Placement(1, releaseNs + 4_000_000L), rule.place(job("a", qos, releaseNs), NOW_NS));
        assertEquals(new Placement(0, NOW_NS), rule.place(job("a", Criticality.HIGH, 0, releaseNs), NOW_NS));
        assertEquals(QueuePolicy.EARLIEST_DEADLINE_FIRST, rule.queuePolicy(1));
        assertEquals(3, new EdfPlacement(2).dispatchersRequired());
        assertThrows(IllegalArgumentException.class, () -> new EdfPlacement(0));
    }

    // ---- FIFO ----

    @Test
    void shouldPutEverythingOnOneDispatcherWithEqualKeysWhenFifo() {
        var rule = new FifoPlacement();
        assertEquals(new Placement(0, 0), rule.place(job("a", Criticality.HIGH, PERIOD_NS, 0), NOW_NS));
        assertEquals(new Placement(0, 0), rule.place(job("a", QoS.NONE, 0), NOW_NS + 1));
        assertEquals(new Placement(2, 0), new FifoPlacement(2).place(job("a", QoS.NONE, 0), NOW_NS));
        assertEquals(QueuePolicy.FIFO, rule.queuePolicy(0));
    }

    @Test
    void shouldGiveLiuLaylandBoundForRateMonotonicAndOneOtherwise() {
        assertEquals(1.0, QueuePolicy.RATE_MONOTONIC.utilizationBound(1), 1e-12);
        assertEquals(2 * (Math.sqrt(2) - 1), QueuePolicy.RATE_MONOTONIC.utilizationBound(2), 1e-12);
        assertEquals(3 * (Math.cbrt(2) - 1), QueuePolicy.RATE_MONOTONIC.utilizationBound(3), 1e-12);
        assertEquals(1.0, QueuePolicy.EARLIEST_DEADLINE_FIRST.utilizationBound(10), 1e-12);
    }
}
