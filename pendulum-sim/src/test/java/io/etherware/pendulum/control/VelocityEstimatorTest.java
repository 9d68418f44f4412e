package io.etherware.pendulum.control;

import static org.junit.jupiter.api.Assertions.assertEquals;
import static org.junit.jupiter.api.Assertions.assertThrows;
import static org.junit.jupiter.api.Assertions.assertTrue;

import org.junit.jupiter.api.Test;

class VelocityEstimatorTest {

    @Test
    void shouldRecoverAConstantRateExactlyWhenUnfiltered() {
        VelocityEstimator estimator = new VelocityEstimator(0L, VelocityEstimator.DEFAULT_MAX_GAP_NS);
        VelocityEstimatorState state = null;
        for (int k = 0; k < 5; k++) {
            long timeUs = 15_000L * k + (k == 3 ? 2_000L : 0L); // one late sample
            double t = timeUs * 1e-6;
            state = estimator.update(2.0 * t, -0.5 * t, timeUs);
        }
        assertEquals(2.0, state.theta1RateRadPerS(), 1e-9);
        assertEquals(-0.5, state.theta2RateRadPerS(), 1e-9);
        assertEquals(5, state.samples());
    }

    @Test
    void shouldApproachAStepInRateWithTheFilterTimeConstant() {
        long tauNs = 10_000_000L;
        VelocityEstimator estimator = new VelocityEstimator(tauNs, VelocityEstimator.DEFAULT_MAX_GAP_NS);
        estimator.update(0.0, 0.0, 0L);
        // A constant rate of 1 rad/s from t = 0: after 10 ms (one τ) the estimate is 1 − 1/e.
        VelocityEstimatorState state = null;
        for (int k = 1; k <= 10; k++) {
            state = estimator.update(k * 1e-3, 0.0, k * 1_000L);
        }
        assertEquals(1.0 - Math.exp(-1.0), state.theta1RateRadPerS(), 1e-12);
    }

    @Test
    void shouldIgnoreADuplicateSampleAndRestartAfterTimeGoesBackwards() {
        VelocityEstimator estimator = new VelocityEstimator(0L, VelocityEstimator.DEFAULT_MAX_GAP_NS);
        estimator.update(0.0, 0.0, 1_000L);
        VelocityEstimatorState moving = estimator.update(0.01, 0.0, 2_000L);
        assertEquals(10.0, moving.theta1RateRadPerS(), 1e-9);

        VelocityEstimatorState duplicate = estimator.update(5.0, 5.0, 2_000L);
        assertEquals(moving, duplicate);

        VelocityEstimatorState backwards = estimator.update(7.0, 0.0, 500L);
        assertEquals(10.0, backwards.theta1RateRadPerS(), 1e-9);
        assertEquals(1, backwards.discontinuities());
        VelocityEstimatorState after = estimator.update(7.001, 0.0, 1_500L);
        assertEquals(1.0, after.theta1RateRadPerS(), 1e-9);
    }

    @Test
    void shouldContinueFromARestoredMemory() {
        VelocityEstimator first = new VelocityEstimator();
        first.update(0.0, 0.0, 0L);
        first.update(0.002, 0.001, 1_000L);
        VelocityEstimator second = new VelocityEstimator();
        second.restore(first.state());

        assertEquals(first.update(0.004, 0.002, 2_000L), second.update(0.004, 0.002, 2_000L));
    }

    @Test
    void shouldRejectANegativeTimeConstant() {
        var error = assertThrows(IllegalArgumentException.class, () -> new VelocityEstimator(-1L, 1_000_000L));
        assertTrue(error.getMessage().startsWith("filterTimeConstantNs=-1"));
    }
}
