package io.etherware.pendulum.plant;

import static org.junit.jupiter.api.Assertions.assertEquals;
import static org.junit.jupiter.api.Assertions.assertThrows;
import static org.junit.jupiter.api.Assertions.assertTrue;

import org.junit.jupiter.api.Test;

class PendulumPlantTest {

    /** Large amplitude: the pendulum 115° from upright, the arm spinning at 4 rad/s. */
    static final PendulumState LARGE_AMPLITUDE = new PendulumState(0.3, 4.0, 2.0, -1.5);
    static final long TEN_SECONDS_NS = 10_000_000_000L;

    /** The largest relative energy error over a run with u = 0. */
    static double maxRelativeEnergyDrift(PendulumParameters parameters, long stepNs, long durationNs) {
        PendulumPlant plant = new PendulumPlant(parameters, LARGE_AMPLITUDE, stepNs);
        double initial = plant.energyJ();
        double worst = 0.0;
        long steps = durationNs / stepNs;
        for (long i = 0; i < steps; i++) {
            plant.step(0.0);
            worst = Math.max(worst, Math.abs(plant.energyJ() - initial));
        }
        return worst / initial;
    }

    @Test
    void shouldConserveEnergyBetterThanOnePpmOverTenSecondsWhenUnforcedAndFrictionless() {
        double drift = maxRelativeEnergyDrift(PendulumParameters.defaults(),
                PendulumPlant.DEFAULT_STEP_NS, TEN_SECONDS_NS);
        System.out.printf("energy drift over 10 s at 0.5 ms: %.3e relative%n", drift);
        assertTrue(drift < 1e-6, () -> "relative energy drift " + drift);
    }

    @Test
    void shouldReduceTheEnergyErrorAboutSixteenfoldWhenHalvingTheStep() {
        // 1 ms -> 0.5 ms (the default): both errors are still far above round-off (~1e-13).
        PendulumParameters parameters = PendulumParameters.defaults();
        double coarse = maxRelativeEnergyDrift(parameters, 1_000_000L, TEN_SECONDS_NS);
        double fine = maxRelativeEnergyDrift(parameters, 500_000L, TEN_SECONDS_NS);
        double ratio = coarse / fine;
        System.out.printf("energy error 1 ms %.3e, 0.5 ms %.3e; ratio %.2f (4th order: 16)%n",
                coarse, fine, ratio);
        assertTrue(ratio > 10 && ratio < 22, () -> "ratio " + ratio);
    }

    /**
     * Bytes allocated so far by the current thread. Through reflection: the tests compile inside
     * the pendulum module, which does not read java.management (they run on the class path).
     */
    static long allocatedBytes() throws ReflectiveOperationException {
        Object threads = Class.forName("java.lang.management.ManagementFactory")
                .getMethod("getThreadMXBean").invoke(null);
        return (long) Class.forName("com.sun.management.ThreadMXBean")
                .getMethod("getThreadAllocatedBytes", long.class)
                .invoke(threads, Thread.currentThread().threadId());
    }

    @Test
    void shouldNotAllocateWhenStepping() throws ReflectiveOperationException {
        PendulumPlant plant = new PendulumPlant(PendulumParameters.defaults().withDamping(1e-4, 1e-5),
                LARGE_AMPLITUDE);
        for (int i = 0; i < 20_000; i++) {
            plant.step(0.01);
        }
        allocatedBytes();
        long before = allocatedBytes();
        for (int i = 0; i < 100_000; i++) {
            plant.step(0.01);
        }
        long allocated = allocatedBytes() - before;
        // 100k steps; a single boxed value or array per step would be megabytes.
        assertTrue(allocated < 4_096, () -> allocated + " bytes allocated by 100000 steps");
    }

    @Test
    void shouldLoseEnergyWhenFrictionIsPresent() {
        PendulumPlant plant = new PendulumPlant(PendulumParameters.defaults().withDamping(1e-3, 1e-4),
                LARGE_AMPLITUDE);
        double initial = plant.energyJ();
        for (int i = 0; i < 2000; i++) {
            plant.step(0.0);
        }
        assertTrue(plant.energyJ() < 0.99 * initial, () -> "energy " + plant.energyJ());
    }

    @Test
    void shouldRejectAStepOutsideTheSupportedRange() {
        var error = assertThrows(IllegalArgumentException.class,
                () -> new PendulumPlant(PendulumParameters.defaults(), PendulumState.upright(0), 0));
        assertTrue(error.getMessage().contains("stepNs=0"));
    }

    @Test
    void shouldNameTheFieldWhenAParameterIsInvalid() {
        var error = assertThrows(IllegalArgumentException.class,
                () -> PendulumParameters.defaults().withInertias(-1.0, 1e-3));
        assertTrue(error.getMessage().startsWith("armInertiaKgM2=-1.0"), error.getMessage());
    }

    @Test
    void shouldStayAtUprightEquilibriumWhenStartedThere() {
        PendulumPlant plant = new PendulumPlant(PendulumParameters.defaults(), PendulumState.upright(1.0));
        for (int i = 0; i < 1000; i++) {
            plant.step(0.0);
        }
        assertEquals(0.0, plant.theta2Rad(), 0.0);
        assertEquals(1.0, plant.theta1Rad(), 0.0);
        assertEquals(500_000_000L, plant.timeNs());
    }
}
