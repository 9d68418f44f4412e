package io.etherware.core.message;

import org.junit.jupiter.api.Test;

import static org.junit.jupiter.api.Assertions.assertEquals;
import static org.junit.jupiter.api.Assertions.assertFalse;
import static org.junit.jupiter.api.Assertions.assertSame;
import static org.junit.jupiter.api.Assertions.assertThrows;
import static org.junit.jupiter.api.Assertions.assertTrue;

class QoSTest {

    @Test
    void shouldNameTheFieldAndValueWhenADurationIsNegative() {
        assertMessage(() -> new QoS(Criticality.HIGH, -1, 0, 0), "periodNs=-1 must not be negative");
        assertMessage(() -> new QoS(Criticality.HIGH, 0, -2, 0), "deadlineNs=-2 must not be negative");
        assertMessage(() -> new QoS(Criticality.HIGH, 0, 0, -3), "wcetNs=-3 must not be negative");
        assertMessage(() -> QoS.NONE.withDeadlineNs(-4), "deadlineNs=-4");
        assertMessage(() -> QoS.NONE.withWcetNs(-5), "wcetNs=-5");
    }

    @Test
    void shouldRequireACriticality() {
        var error = assertThrows(NullPointerException.class, () -> new QoS(null, 0, 0, 0));
        assertEquals("criticality", error.getMessage());
    }

    @Test
    void shouldTreatZeroAsNotSpecified() {
        assertFalse(QoS.NONE.hasPeriod());
        assertFalse(QoS.NONE.hasDeadline());
        assertFalse(QoS.NONE.hasWcet());
        QoS full = new QoS(Criticality.LOW, 1, 2, 3);
        assertTrue(full.hasPeriod() && full.hasDeadline() && full.hasWcet());
    }

    @Test
    void shouldUseThePeriodAsImplicitDeadlineWhenPeriodic() {
        QoS periodic = QoS.periodic(Criticality.HIGH, 15_000_000);
        assertEquals(new QoS(Criticality.HIGH, 15_000_000, 15_000_000, 0), periodic);
        assertEquals(2_000_000, periodic.withWcetNs(2_000_000).wcetNs());
        assertEquals(10_000_000, periodic.withDeadlineNs(10_000_000).deadlineNs());
        assertMessage(() -> QoS.periodic(Criticality.HIGH, 0), "periodNs=0 must be > 0");
    }

    @Test
    void shouldReturnTheSharedBestEffortValueForCriticalityNone() {
        assertSame(QoS.NONE, QoS.of(Criticality.NONE));
        assertEquals(new QoS(Criticality.MIDDLE, 0, 0, 0), QoS.of(Criticality.MIDDLE));
        assertTrue(Criticality.HIGH.compareTo(Criticality.LOW) > 0, "ordered from least to most critical");
    }

    private static void assertMessage(Runnable action, String expected) {
        var error = assertThrows(IllegalArgumentException.class, action::run);
        assertTrue(error.getMessage().contains(expected), error.getMessage());
    }
}
