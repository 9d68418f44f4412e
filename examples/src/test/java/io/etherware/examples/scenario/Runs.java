package io.etherware.examples.scenario;

import io.etherware.pendulum.components.ControlCycle;
import java.util.ArrayList;
import java.util.List;

/** Synthetic runs for the output tests: a 15 ms loop from t = 0 with a chosen θ2 trace and cycles. */
public final class Runs {

    public static final long PERIOD_NS = 15_000_000L;

    private Runs() {
    }

    /** A commanded cycle released at {@code k * period} (origin 0), handled {@code latenessNs} late, commanded {@code responseNs} after release. */
    public static ControlCycle commanded(long k, long latenessNs, long responseNs) {
        long releaseNs = PERIOD_NS + k * PERIOD_NS;
        return new ControlCycle(k, releaseNs, releaseNs + latenessNs, releaseNs + responseNs,
                ControlCycle.Outcome.COMMANDED, 0.0, 0.0, 0.0, 0.0, 0L, 0.01, 1);
    }

    /** A cycle whose reading failed. */
    public static ControlCycle missed(long k) {
        long releaseNs = PERIOD_NS + k * PERIOD_NS;
        return new ControlCycle(k, releaseNs, releaseNs, releaseNs + 10_000_000L, ControlCycle.Outcome.MISSED,
                Double.NaN, Double.NaN, Double.NaN, Double.NaN, -1L, Double.NaN, 1);
    }

    /** Samples every period from t = 0 with the given θ2 values (θ1 = θ2 / 2, torque 0.01). */
    public static ProbeSamples samples(double... theta2Rad) {
        int n = theta2Rad.length;
        long[] time = new long[n];
        double[] theta1 = new double[n];
        double[] torque = new double[n];
        for (int i = 0; i < n; i++) {
            time[i] = i * PERIOD_NS;
            theta1[i] = theta2Rad[i] / 2;
            torque[i] = 0.01;
        }
        return new ProbeSamples(time, theta1, theta2Rad.clone(), torque);
    }

    /** A run from origin 0, first release one period later, ending at {@code endNs}. */
    public static ScenarioRun run(String key, ProbeSamples samples, List<ControlCycle> cycles,
            List<ScenarioEvent> events, long endNs) {
        return new ScenarioRun(key, "run " + key, PERIOD_NS, 0L, PERIOD_NS, endNs, samples, cycles, events,
                new ArrayList<>(List.of("note of " + key)));
    }
}
