package io.etherware.examples.output;

import static org.junit.jupiter.api.Assertions.assertEquals;
import static org.junit.jupiter.api.Assertions.assertTrue;

import io.etherware.examples.scenario.ProbeSamples;
import io.etherware.examples.scenario.Runs;
import io.etherware.examples.scenario.ScenarioEvent;
import io.etherware.examples.scenario.ScenarioRun;
import io.etherware.pendulum.components.ControlCycle;
import java.awt.image.BufferedImage;
import java.nio.file.Files;
import java.nio.file.Path;
import java.util.ArrayList;
import java.util.List;
import java.util.Random;
import javax.imageio.ImageIO;
import org.junit.jupiter.api.BeforeAll;
import org.junit.jupiter.api.Test;
import org.junit.jupiter.api.io.TempDir;
import org.knowm.xchart.XYChart;

class TracePlotsTest {

    private static final long P = Runs.PERIOD_NS;

    @BeforeAll
    static void headless() {
        System.setProperty("java.awt.headless", "true");
    }

    @Test
    void shouldSaveFourPanelsOnOneTimeAxisAsAPngAndAnSvgOfTheSameSize(@TempDir Path dir) throws Exception {
        StackedChart figure = TracePlots.of(run("rt", 200, 0.005, false), "one run");

        List<Path> files = figure.save(dir.resolve("stress-rt"));

        assertEquals(List.of(dir.resolve("stress-rt.png"), dir.resolve("stress-rt.svg")), files);
        assertEquals(4, figure.panelCount());
        BufferedImage png = ImageIO.read(files.get(0).toFile());
        assertEquals(StackedChart.WIDTH, png.getWidth());
        assertEquals(figure.height(), png.getHeight());
        String svg = Files.readString(files.get(1));
        assertTrue(svg.contains("viewBox=\"0 0 800 " + figure.height() + "\""), svg.substring(0, 400));
        for (int p = 0; p < 4; p++) {
            assertEquals(0.0, figure.panel(p).getStyler().getXAxisMin(), "panel " + p + " starts at 0 s");
            assertEquals(200 * P / 1e9, figure.panel(p).getStyler().getXAxisMax(), 1e-9,
                    "panel " + p + " ends with the run");
        }
    }

    @Test
    void shouldScaleThePendulumToItsOwnRangeNotTheArms() {
        StackedChart figure = TracePlots.of(run("rt", 400, 0.005, false), "small θ2");

        XYChart theta2 = figure.panel(1);
        assertEquals(0.005 * 1.15, theta2.getStyler().getYAxisMax(), 1e-6);
        assertEquals(-0.005 * 1.15, theta2.getStyler().getYAxisMin(), 1e-6);
        XYChart theta1 = figure.panel(0);
        assertTrue(theta1.getStyler().getYAxisMax() > 0.1, "θ1 swings ±0.1 rad: " + theta1.getStyler().getYAxisMax());
        assertTrue(figure.panel(3).getStyler().isYAxisLogarithmic(), "lateness on a log scale");
    }

    @Test
    void shouldScaleAComparisonToTheRunThatStayedUpAndShowTheFallenRunsFullLateness() {
        ScenarioRun fell = run("fifo", 400, 0.005, true);
        ScenarioRun up = run("rt", 400, 0.01, false);

        StackedChart figure = TracePlots.of(List.of(fell, up), "fifo vs rt");

        assertEquals(0.01 * 1.15, figure.panel(1).getStyler().getYAxisMax(), 1e-6);
        // One Tick of each run was 800 ms late: the log scale shows it, whole, with room above.
        assertEquals(1600.0, figure.panel(3).getStyler().getYAxisMax(), 1e-9);
        assertTrue(figure.panel(3).getSeriesMap().values().stream()
                .anyMatch(s -> s.isShowInLegend() && s.getLabel().equals("run fifo (fell at 3.09 s)")),
                "the legend names the runs and when one fell");
    }

    /** A minute at 15 ms, two runs overlaid: 4,000 noisy samples and cycles each. */
    @Test
    void shouldKeepTheSvgOfTwoOneMinuteRunsWellUnder300Kilobytes() throws Exception {
        int n = 4_000;
        StackedChart figure = TracePlots.of(List.of(run("fifo", n, 0.02, false), run("rt", n, 0.004, false)),
                "a minute");

        String svg = figure.toSvg();

        assertTrue(svg.length() < 250_000, "SVG of " + svg.length() + " bytes");
        assertTrue(svg.endsWith("</svg>\n") || svg.endsWith("</svg>"), "a whole document");
    }

    /**
     * {@code n} samples every period: θ2 noise of amplitude {@code theta2Rad} (rising past the fall
     * threshold from the middle if {@code falls}), θ1 a ±0.1 rad swing, u noise, Ticks a few µs late
     * and one 800 ms late; a stress band and an upgrade.
     */
    private static ScenarioRun run(String key, int n, double theta2Rad, boolean falls) {
        var random = new Random(key.hashCode());
        long[] time = new long[n];
        double[] theta1 = new double[n];
        double[] theta2 = new double[n];
        double[] torque = new double[n];
        List<ControlCycle> cycles = new ArrayList<>();
        for (int i = 0; i < n; i++) {
            time[i] = i * P;
            theta1[i] = 0.1 * Math.sin(i / 50.0);
            theta2[i] = falls && i >= n / 2 ? 0.1 * (i - n / 2) : theta2Rad * (2 * random.nextDouble() - 1);
            torque[i] = 0.05 * (2 * random.nextDouble() - 1);
            long lateness = i == n / 3 ? 800_000_000L : 2_000 + random.nextInt(50_000);
            cycles.add(Runs.commanded(i, lateness, lateness + 3_000_000L));
        }
        theta2[n / 4] = falls ? theta2[n / 4] : theta2Rad; // the extreme, exactly
        List<ScenarioEvent> events = List.of(
                new ScenarioEvent(n / 5 * P, ScenarioEvent.Kind.STRESS_START, "stress 1 start"),
                new ScenarioEvent(n / 4 * P, ScenarioEvent.Kind.STRESS_END, "stress 1 end"),
                new ScenarioEvent(n / 2 * P, ScenarioEvent.Kind.UPGRADE, "upgrade"));
        return Runs.run(key, new ProbeSamples(time, theta1, theta2, torque), cycles, events, n * P);
    }
}
