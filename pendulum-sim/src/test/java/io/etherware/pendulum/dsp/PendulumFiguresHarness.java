package io.etherware.pendulum.dsp;

import io.etherware.pendulum.control.BalanceControl;
import io.etherware.pendulum.control.GainSet;
import io.etherware.pendulum.control.LoopAnalysis;
import io.etherware.pendulum.control.VelocityEstimator;
import io.etherware.pendulum.linalg.Complex;
import io.etherware.pendulum.plant.LinearModel;
import io.etherware.pendulum.plant.PendulumParameters;
import io.etherware.pendulum.plant.PendulumPlant;
import io.etherware.pendulum.plant.PendulumState;
import io.etherware.pendulum.serial.SimulatedSerialLink;
import java.util.List;
import java.util.stream.Collectors;

/**
 * Prints the design figures of the pendulum: parameters, open-loop eigenvalues, the gain sets,
 * the discrete closed-loop eigenvalue magnitudes at 15 ms and 1 ms, the integrator's energy
 * drift and convergence ratio, and lock-step settling times. Deterministic; not part of the
 * test suite. Run after {@code ./mvnw -pl pendulum-sim -am verify}:
 *
 * <pre>
 * $JAVA_HOME/bin/java -cp pendulum-sim/target/classes:pendulum-sim/target/test-classes:etherware-core/target/classes:\
 *   ~/.m2/repository/org/slf4j/slf4j-api/2.0.20/slf4j-api-2.0.20.jar \
 *   io.etherware.pendulum.dsp.PendulumFiguresHarness
 * </pre>
 */
public final class PendulumFiguresHarness {

    private PendulumFiguresHarness() {}

    /** Prints the figures. */
    public static void main(String[] args) {
        PendulumParameters parameters = PendulumParameters.defaults();
        LinearModel model = LinearModel.linearize(parameters, 0.0);
        System.out.printf("m=%.3f kg l1=%.3f m l2=%.3f m J1=%.4e kg·m² J2=%.4e kg·m²%n",
                parameters.pendulumMassKg(), parameters.armLengthM(),
                parameters.pendulumCenterOfMassM(), parameters.armInertiaKgM2(),
                parameters.pendulumInertiaKgM2());
        System.out.println("open-loop eigenvalues: " + model.eigenvalues()
                + "; unstable " + model.mostUnstableEigenvalue() + " rad/s");

        for (GainSet gains : List.of(GainSet.v1Soft(parameters), GainSet.v2Tight(parameters))) {
            System.out.printf("%n%s poles %s%n  K = [%.5f, %.5f, %.5f, %.5f]%n", gains.name(),
                    gains.polesRadPerS(), gains.kTheta1NmPerRad(), gains.kTheta1RateNmsPerRad(),
                    gains.kTheta2NmPerRad(), gains.kTheta2RateNmsPerRad());
            // Sample-to-torque delays of the lock-step rigs (see SERIAL-PROTOCOL.md, Board timing):
            // 15 ms at 115200 baud with 0.5 ms board cycles: 3.0 ms; 1 ms at 921600 with 0.1 ms: 0.4 ms.
            report(model, gains, 15_000_000L, 3_000_000L);
            report(model, gains, 1_000_000L, 400_000L);
        }

        double drift = energyDrift(parameters, PendulumPlant.DEFAULT_STEP_NS);
        double coarse = energyDrift(parameters, 1_000_000L);
        System.out.printf("%nenergy drift over 10 s (u=0, no friction, θ2(0)=2 rad): %.3e relative at 0.5 ms;"
                + " %.3e at 1 ms; ratio %.2f%n", drift, coarse, coarse / drift);

        for (long periodNs : new long[] {15_000_000L, 1_000_000L}) {
            for (GainSet gains : List.of(GainSet.v1Soft(parameters), GainSet.v2Tight(parameters))) {
                boolean fast = periodNs < 5_000_000L;
                LockStepRig rig = new LockStepRig(fast ? SimulatedSerialLink.Config.defaults().withBaudRate(921_600)
                        : SimulatedSerialLink.Config.defaults(),
                        fast ? DspBoardConfig.defaults().withStep(java.time.Duration.ofNanos(100_000L)) : DspBoardConfig.defaults(),
                        new PendulumState(0.0, 0.0, 0.05, 0.0));
                rig.control(new BalanceControl(gains, 0.0, DspBoardConfig.DEFAULT_MAX_TORQUE_NM,
                        VelocityEstimator.DEFAULT_FILTER_TIME_CONSTANT_NS), periodNs, 6_000_000_000L);
                System.out.printf("lock-step %s at %s ms from θ2=0.05: inside ±0.01 rad after %.3f s%n",
                        gains.name(), periodNs / 1e6, rig.probe.lastOutsideBandNs * 1e-9);
            }
        }
    }

    private static void report(LinearModel model, GainSet gains, long periodNs, long delayNs) {
        List<Complex> ideal = LoopAnalysis.ideal(model, gains, periodNs);
        List<Complex> implemented = LoopAnalysis.asImplemented(model, gains, periodNs, delayNs,
                VelocityEstimator.DEFAULT_FILTER_TIME_CONSTANT_NS);
        System.out.printf("  T=%s ms ideal z = %s, |z| = %s%n  T=%s ms with estimator, %.1f ms delay |z| = %s"
                + " (slowest decay %.2f /s)%n", periodNs / 1e6, ideal, magnitudes(ideal), periodNs / 1e6,
                delayNs / 1e6, magnitudes(implemented),
                LoopAnalysis.slowestDecayRatePerS(implemented, periodNs));
    }

    private static String magnitudes(List<Complex> eigenvalues) {
        return eigenvalues.stream().map(z -> String.format("%.4f", z.abs()))
                .collect(Collectors.joining(", ", "[", "]"));
    }

    private static double energyDrift(PendulumParameters parameters, long stepNs) {
        PendulumPlant plant = new PendulumPlant(parameters, new PendulumState(0.3, 4.0, 2.0, -1.5), stepNs);
        double initial = plant.energyJ();
        double worst = 0;
        for (long i = 0; i < 10_000_000_000L / stepNs; i++) {
            plant.step(0.0);
            worst = Math.max(worst, Math.abs(plant.energyJ() - initial));
        }
        return worst / initial;
    }
}
