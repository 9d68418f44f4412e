package io.etherware.pendulum.components;

import io.etherware.pendulum.control.GainSet;
import io.etherware.pendulum.plant.PendulumState;
import io.etherware.pendulum.serial.BoardStatus;
import java.util.Arrays;
import java.util.List;

/**
 * Measures the components' 15 ms loop in real time ({@link RealTimeLoop}: FIFO dispatcher, DSP
 * board behind a simulated 115200-baud link, test ticker) and prints percentiles of the
 * controller's start lateness (release to Tick handled), its response (release to torque sent)
 * and the period between successive torque commands, with the largest |θ2| of the plant. The
 * first 2 s are warm-up and not counted. Not part of the test suite. Run after
 * {@code ./mvnw -pl pendulum-sim -am verify -DskipTests}:
 *
 * <pre>
 * java --enable-native-access=ALL-UNNAMED \
 *   -cp pendulum-sim/target/classes:pendulum-sim/target/test-classes:etherware-core/target/classes:\
 *   $(ls ~/.m2/repository/org/slf4j/slf4j-api/2.0.*&#47;slf4j-api-*.jar | tail -1) \
 *   io.etherware.pendulum.components.PendulumLoopHarness [seconds=12] [normal] [swap]
 * </pre>
 *
 * {@code normal} keeps every thread at normal priority (the default raises the board, the ticker
 * and the dispatcher to SCHED_FIFO); {@code swap} upgrades V1 to V2 half way.
 */
public final class PendulumLoopHarness {

    private static final long WARM_UP_NS = 2_000_000_000L;

    private PendulumLoopHarness() {}

    /** Runs the loop and prints the figures. */
    public static void main(String[] args) throws Exception {
        List<String> options = List.of(args);
        long seconds = options.stream().filter(a -> a.matches("\\d+")).mapToLong(Long::parseLong).findFirst().orElse(12);
        boolean realTime = !options.contains("normal");
        boolean swap = options.contains("swap");
        GainSet v1 = GainSet.v1Soft(RealTimeLoop.PARAMETERS);
        try (RealTimeLoop loop = new RealTimeLoop(new PendulumState(0.0, 0.0, 0.05, 0.0), v1, realTime).start()) {
            if (swap) {
                Thread.sleep(seconds * 500L);
                loop.node.swap(PendulumController.DEFAULT_PROFILE, PendulumController.factory(RealTimeLoop.CONFIG,
                        GainSet.v2Tight(RealTimeLoop.PARAMETERS), loop.recorder));
                Thread.sleep(seconds * 500L);
            } else {
                Thread.sleep(seconds * 1_000L);
            }
            BoardStatus board = loop.board.status(); // before the watchdog notices the ticker stopped
            loop.stopTicker();
            report(loop, board, seconds, realTime, swap);
        }
    }

    private static void report(RealTimeLoop loop, BoardStatus board, long seconds, boolean realTime, boolean swap) {
        List<ControlCycle> cycles = loop.recorder.cycles();
        long originNs = cycles.getFirst().releaseNs();
        List<ControlCycle> measured = cycles.stream().filter(c -> c.releaseNs() - originNs >= WARM_UP_NS).toList();
        long[] lateness = measured.stream().mapToLong(ControlCycle::startLatenessNs).toArray();
        long[] response = measured.stream().filter(c -> c.outcome() == ControlCycle.Outcome.COMMANDED)
                .mapToLong(ControlCycle::responseNs).toArray();
        long[] period = new long[measured.size()];
        int periods = 0;
        for (int i = 1; i < measured.size(); i++) {
            ControlCycle previous = measured.get(i - 1);
            ControlCycle current = measured.get(i);
            if (current.cycle() == previous.cycle() + 1 && current.outcome() == ControlCycle.Outcome.COMMANDED
                    && previous.outcome() == ControlCycle.Outcome.COMMANDED) {
                period[periods++] = current.readoutNs() - previous.readoutNs();
            }
        }
        ControllerState state = loop.controllerState();
        System.out.printf("components loop, %d s (%d cycles after a 2 s warm-up), 15 ms, FIFO dispatcher, %s%s%n",
                seconds, measured.size(), realTime ? "SCHED_FIFO board/ticker/dispatcher (dispatcher raised: "
                        + loop.dispatcherRaised() + ")" : "normal priority", swap ? ", V1→V2 swap half way" : "");
        System.out.println("                              p50      p90      p99    p99.9      max   (ms)");
        print("start lateness (Tick)", lateness);
        print("release → torque sent", response);
        print("torque-to-torque period", Arrays.copyOf(period, periods));
        long[] jitter = Arrays.stream(period, 0, periods).map(p -> Math.abs(p - RealTimeLoop.PERIOD_NS)).toArray();
        print("|period − 15 ms|", jitter);
        System.out.printf("max |θ2| (plant, at releases) %.4f rad; ticks %d (skipped by the ticker %d, worst ticker wake"
                + " %.3f ms)%n", loop.ticker.maxAbsTheta2Rad(), loop.ticker.sent(), loop.ticker.skipped(),
                loop.ticker.maxWakeLatenessNs() / 1e6);
        System.out.printf("controller: ticks %d, commands %d, missed %d, late %d, abandoned %d, skipped %d%n",
                state.ticks(), state.commands(), state.missedReplies(), state.lateReplies(), state.abandonedCycles(),
                state.skippedTicks());
        System.out.println("proxy: " + loop.proxyCounters());
        System.out.println("board (while running): " + board + ", late board cycles " + loop.board.lateCycles());
        System.out.println("node: " + loop.node.stats());
    }

    private static void print(String name, long[] valuesNs) {
        if (valuesNs.length == 0) {
            System.out.printf("%-26s (none)%n", name);
            return;
        }
        long[] sorted = valuesNs.clone();
        Arrays.sort(sorted);
        System.out.printf("%-26s %8.3f %8.3f %8.3f %8.3f %8.3f%n", name, percentile(sorted, 0.50),
                percentile(sorted, 0.90), percentile(sorted, 0.99), percentile(sorted, 0.999),
                sorted[sorted.length - 1] / 1e6);
    }

    private static double percentile(long[] sorted, double quantile) {
        int index = (int) Math.ceil(quantile * sorted.length) - 1;
        return sorted[Math.max(0, Math.min(sorted.length - 1, index))] / 1e6;
    }
}
