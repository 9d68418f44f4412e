package io.etherware.pendulum.control;

import static org.junit.jupiter.api.Assertions.assertEquals;

import java.util.List;
import org.junit.jupiter.api.Test;

class StateFeedbackLawTest {

    private static final GainSet GAINS = new GainSet("test", 7, List.of(), 1.0, 2.0, 3.0, 4.0);

    @Test
    void shouldComputeMinusKTimesTheErrorFromTheSetPoint() {
        StateFeedbackLaw law = new StateFeedbackLaw(GAINS, 0.5, 100.0);
        double u = law.torqueNm(1.5, 0.1, 0.2, -0.3);
        assertEquals(-(1.0 * 1.0 + 2.0 * 0.1 + 3.0 * 0.2 + 4.0 * -0.3), u, 1e-12);
    }

    @Test
    void shouldSaturateAtTheTorqueLimit() {
        StateFeedbackLaw law = new StateFeedbackLaw(GAINS, 0.0, 0.5);
        assertEquals(-0.5, law.torqueNm(10.0, 0, 0, 0), 0.0);
        assertEquals(0.5, law.torqueNm(-10.0, 0, 0, 0), 0.0);
        assertEquals(0.0, StateFeedbackLaw.clamp(Double.NaN, 0.5), 0.0);
    }

    @Test
    void shouldTreatAFullTurnOfThePendulumAsUpright() {
        StateFeedbackLaw law = new StateFeedbackLaw(GAINS, 0.0, 100.0);
        assertEquals(law.torqueNm(0, 0, 0.1, 0), law.torqueNm(0, 0, 0.1 + 2 * Math.PI, 0), 1e-12);
        assertEquals(Math.PI, StateFeedbackLaw.wrapToPi(-Math.PI), 0.0);
    }

    @Test
    void shouldCountSaturatedCyclesAndKeepTheEstimatorAcrossAGainChange() {
        BalanceControl control = new BalanceControl(GAINS, 0.0, 0.5, 0L);
        control.update(0.0, 0.0, 0L);
        control.update(1.0, 0.0, 1_000L); // 1000 rad/s arm rate: saturates
        control.useGains(new GainSet("other", 8, List.of(), 0, 0, 0, 0));
        BalanceControlState state = control.state();
        assertEquals(2, state.cycles());
        assertEquals(1, state.saturatedCycles());
        assertEquals(8, state.gains().version());
        assertEquals(1000.0, state.estimator().theta1RateRadPerS(), 1e-9);
    }
}
