package io.etherware.pendulum.control;

import static org.junit.jupiter.api.Assertions.assertEquals;
import static org.junit.jupiter.api.Assertions.assertThrows;
import static org.junit.jupiter.api.Assertions.assertTrue;

import io.etherware.pendulum.linalg.Complex;
import io.etherware.pendulum.plant.LinearModel;
import io.etherware.pendulum.plant.PendulumParameters;
import java.util.List;
import org.junit.jupiter.api.Test;
import org.junit.jupiter.params.ParameterizedTest;
import org.junit.jupiter.params.provider.CsvSource;

class LoopAnalysisTest {

    static final PendulumParameters PARAMETERS = PendulumParameters.defaults();
    static final LinearModel MODEL = LinearModel.linearize(PARAMETERS, 0.0);
    /** Every mode must decay at least this fast, at any period: the margin inside the unit circle. */
    static final double MIN_DECAY_RATE_PER_S = 1.0;

    static GainSet gains(String version) {
        return version.equals("V1") ? GainSet.v1Soft(PARAMETERS) : GainSet.v2Tight(PARAMETERS);
    }

    @ParameterizedTest(name = "{0} at {1} ns, delay {2} ns")
    @CsvSource({
        "V1, 15000000, 4000000",
        "V2, 15000000, 4000000",
        "V1, 1000000, 500000",
        "V2, 1000000, 500000",
    })
    void shouldBeStableWithMarginWhenDiscretizedAtTheControlPeriod(String version, long periodNs,
            long delayNs) {
        GainSet gainSet = gains(version);
        List<Complex> ideal = LoopAnalysis.ideal(MODEL, gainSet, periodNs);
        List<Complex> implemented = LoopAnalysis.asImplemented(MODEL, gainSet, periodNs, delayNs,
                VelocityEstimator.DEFAULT_FILTER_TIME_CONSTANT_NS);

        LoopAnalysis.requireStable(ideal, periodNs, MIN_DECAY_RATE_PER_S, version + " ideal");
        LoopAnalysis.requireStable(implemented, periodNs, MIN_DECAY_RATE_PER_S,
                version + " as implemented");
        assertEquals(4, ideal.size());
        assertEquals(9, implemented.size());
    }

    @Test
    void shouldMapTheContinuousPolesWhenTheStateIsFedBackIdeally() {
        // Without delay or estimator, the ZOH loop's eigenvalues approach e^{pT} as T shrinks.
        long periodNs = 100_000L;
        GainSet gainSet = GainSet.v2Tight(PARAMETERS);
        List<Complex> ideal = LoopAnalysis.ideal(MODEL, gainSet, periodNs);
        for (Complex pole : gainSet.polesRadPerS()) {
            Complex expected = pole.expTimes(periodNs * 1e-9);
            double nearest = ideal.stream().mapToDouble(z -> z.minus(expected).abs()).min().orElseThrow();
            assertTrue(nearest < 1e-4, () -> "expected " + expected + " in " + ideal);
        }
    }

    @Test
    void shouldBeUnstableWhenTheControlPeriodIsFarTooLong() {
        long periodNs = 250_000_000L;
        List<Complex> ideal = LoopAnalysis.ideal(MODEL, GainSet.v2Tight(PARAMETERS), periodNs);
        assertTrue(LoopAnalysis.spectralRadius(ideal) > 1.0, () -> "eigenvalues " + ideal);
        assertThrows(IllegalStateException.class,
                () -> LoopAnalysis.requireStable(ideal, periodNs, 0.0, "250 ms"));
    }

    @Test
    void shouldGiveTheTwoGainSetsVisiblyDifferentDynamics() {
        GainSet soft = GainSet.v1Soft(PARAMETERS);
        GainSet tight = GainSet.v2Tight(PARAMETERS);
        long periodNs = 15_000_000L;
        double softRate = LoopAnalysis.slowestDecayRatePerS(
                LoopAnalysis.ideal(MODEL, soft, periodNs), periodNs);
        double tightRate = LoopAnalysis.slowestDecayRatePerS(
                LoopAnalysis.ideal(MODEL, tight, periodNs), periodNs);
        assertTrue(tightRate > 2 * softRate, () -> "soft " + softRate + "/s, tight " + tightRate + "/s");
        assertTrue(Math.abs(tight.kTheta1NmPerRad()) > 3 * Math.abs(soft.kTheta1NmPerRad()));
    }

    @ParameterizedTest(name = "{0}")
    @CsvSource({"V1", "V2"})
    void shouldStayStableWhenA15msCycleIsLostAndTheTorqueIsHeldFor30ms(String version) {
        List<Complex> held = LoopAnalysis.asImplemented(MODEL, gains(version), 30_000_000L,
                4_000_000L, VelocityEstimator.DEFAULT_FILTER_TIME_CONSTANT_NS);
        LoopAnalysis.requireStable(held, 30_000_000L, 0.0, version + " at 30 ms");
    }
}
