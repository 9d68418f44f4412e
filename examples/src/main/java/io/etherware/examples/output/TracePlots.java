package io.etherware.examples.output;

import io.etherware.examples.scenario.ProbeSamples;
import io.etherware.examples.scenario.RunSummary;
import io.etherware.examples.scenario.ScenarioEvent;
import io.etherware.examples.scenario.ScenarioRun;
import io.etherware.pendulum.components.ControlCycle;
import io.etherware.pendulum.components.ControllerConfig;
import java.awt.BasicStroke;
import java.awt.Color;
import java.math.BigDecimal;
import java.util.ArrayList;
import java.util.Arrays;
import java.util.Comparator;
import java.util.List;
import java.util.Locale;
import org.knowm.xchart.XYChart;
import org.knowm.xchart.XYSeries;
import org.knowm.xchart.style.markers.SeriesMarkers;

/**
 * The scenarios' plots, in the spirit of the paper's Fig. 9 and 11, as a control engineer reads a
 * loop: four panels on one time axis, from the same data as {@link TraceCsv}: the arm θ1 with its
 * set point, the pendulum θ2 on a scale of its own, the motor torque u, and each Tick's start
 * lateness on a log scale with the control period drawn. Stress activations are shaded and
 * upgrades or migrations marked in every panel.
 *
 * <p>Several runs (original Etherware and Etherware-RT) are overlaid, one colour each, rather
 * than set side by side: the point is what each does at the same moment of the same stress, and
 * one full-width column keeps the time resolution. Each angle and torque panel is scaled to the
 * runs that kept the pendulum up (to all runs, up to their falls, if none did), so a run that
 * falls leaves the panel instead of flattening the others; the lateness panel, on a log scale,
 * shows every run whole.
 *
 * <p>Points are thinned to the smallest and largest per pixel column before drawing
 * ({@link Decimation}), and {@link StackedChart} writes the SVG compactly.
 *
 * <p>Stateless and thread-safe; charts are built and encoded headless (set
 * {@code java.awt.headless=true} before the first one).
 */
public final class TracePlots {

    /** The arm's set point of the scenarios' controllers, rad. */
    static final double SET_POINT_RAD = ControllerConfig.defaults().theta1ReferenceRad();
    /** The torque the controllers clamp to, N·m. */
    static final double TORQUE_LIMIT_NM = ControllerConfig.defaults().maxTorqueNm();
    /** The smallest lateness the log scale shows, ms: a microsecond. */
    static final double LATENESS_FLOOR_MS = 0.001;

    private static final double MAX_ANGLE_RAD = 3 * Math.PI;
    private static final int THETA1 = 0;
    private static final int THETA2 = 1;
    private static final int TORQUE = 2;
    private static final int LATENESS = 3;
    private static final List<String> Y_TITLES = List.of("θ1 arm (rad)", "θ2 pendulum (rad)", "u motor (N·m)",
            "Tick lateness (ms)");

    private static final Color STRESS_SHADE = new Color(255, 170, 0, 70);
    private static final Color REFERENCE = new Color(120, 120, 120);
    private static final Color MARK = new Color(40, 150, 60);
    private static final Color FALL = new Color(150, 0, 0);
    private static final Color SINGLE_RUN = new Color(30, 90, 200);
    private static final Color[] RUN_COLORS = {new Color(200, 40, 40), new Color(30, 90, 200),
        new Color(40, 150, 60), new Color(120, 60, 160)};
    private static final BasicStroke LINE = new BasicStroke(1.0f, BasicStroke.CAP_ROUND, BasicStroke.JOIN_ROUND);
    private static final BasicStroke DASHED = new BasicStroke(1.0f, BasicStroke.CAP_BUTT, BasicStroke.JOIN_MITER,
            10.0f, new float[] {6.0f, 4.0f}, 0.0f);
    private static final BasicStroke DOTTED = new BasicStroke(1.5f, BasicStroke.CAP_BUTT, BasicStroke.JOIN_MITER,
            10.0f, new float[] {2.0f, 3.0f}, 0.0f);

    private TracePlots() {
    }

    /** One run's four panels. */
    public static StackedChart of(ScenarioRun run, String title) {
        return of(List.of(run), title);
    }

    /** The four panels with {@code runs} overlaid, stress shaded from the first. */
    public static StackedChart of(List<ScenarioRun> runs, String title) {
        if (runs.isEmpty()) {
            throw new IllegalArgumentException("runs is empty: nothing to plot");
        }
        double endS = Math.max(1e-3, runs.stream().mapToDouble(ScenarioRun::durationS).max().orElse(1.0));
        var figure = new StackedChart(title, Y_TITLES, 0.0, endS);
        List<Trace> traces = runs.stream().map(run -> Trace.of(run, endS)).toList();
        List<Trace> scaleBy = traces.stream().anyMatch(t -> !t.fell()) ? traces.stream().filter(t -> !t.fell())
                .toList() : traces;
        double[][] ranges = {theta1Range(scaleBy), symmetric(scaleBy, THETA2, 0.005, MAX_ANGLE_RAD),
            symmetric(scaleBy, TORQUE, 0.01, 1.15 * TORQUE_LIMIT_NM), latenessRange(traces)};

        for (int p = 0; p < figure.panelCount(); p++) {
            XYChart panel = figure.panel(p);
            double lo = ranges[p][0];
            double hi = ranges[p][1];
            panel.getStyler().setYAxisMin(lo).setYAxisMax(hi);
            panel.getStyler().setYAxisDecimalPattern(p == LATENESS ? "0.###" : "0.0##");
            panel.getStyler().setYAxisLogarithmic(p == LATENESS);
            // A log axis has a grid line at every 1..9 of each decade: too dense for a short panel.
            panel.getStyler().setPlotGridHorizontalLinesVisible(p != LATENESS);
            shadeStress(panel, runs.getFirst(), lo, hi, p);
            markEvents(panel, runs, lo, hi, p);
        }
        for (int i = 0; i < traces.size(); i++) {
            Trace trace = traces.get(i);
            Color color = traces.size() == 1 ? SINGLE_RUN : RUN_COLORS[i % RUN_COLORS.length];
            String name = trace.run().title() + (trace.fell() ? String.format(Locale.ROOT, " (fell at %.2f s)",
                    trace.fellAtS()) : "");
            for (int p = 0; p < figure.panelCount(); p++) {
                XYChart panel = figure.panel(p);
                double lo = ranges[p][0];
                double hi = ranges[p][1];
                double[][] xy = p == LATENESS ? trace.lateness() : new double[][] {trace.timeS(), trace.values(p)};
                double[] y = p == LATENESS ? xy[1] : leavingThePanel(trace.untilFallen(xy[1]), lo, hi);
                Decimation.Series thin = Decimation.minMaxPerColumn(xy[0], y, 0.0, endS, StackedChart.PLOT_WIDTH);
                if (Arrays.stream(thin.y()).allMatch(Double::isNaN)) {
                    continue; // nothing to draw (no cycles recorded, say), and XChart wants data
                }
                XYSeries series = line(panel, "run " + i, thin.x(), thin.y(), color, LINE);
                series.setShowInLegend(false);
                if (p == LATENESS && traces.size() > 1) {
                    series.setLabel(name);
                    series.setShowInLegend(true);
                }
                if (trace.fell()) {
                    XYSeries fall = line(panel, "fall " + i, new double[] {trace.fellAtS(), trace.fellAtS()},
                            new double[] {lo, hi}, traces.size() == 1 ? FALL : color, DOTTED);
                    fall.setShowInLegend(p == LATENESS && traces.size() == 1);
                    fall.setLabel(String.format(Locale.ROOT, "fell at %.2f s (|θ2| > %s rad)", trace.fellAtS(),
                            RunSummary.FALL_THRESHOLD_RAD));
                }
            }
        }
        references(figure, endS, ranges, traces.getFirst().run().periodNs() / 1e6);
        return figure;
    }

    /** One run's samples and cycles in plot units, and where it fell. */
    private record Trace(ScenarioRun run, double[] timeS, double[] theta1Rad, double[] theta2Rad, double[] torqueNm,
            double[][] lateness, int upTo, double fellAtS) {

        static Trace of(ScenarioRun run, double endS) {
            ProbeSamples samples = run.samples();
            double[] timeS = new double[samples.size()];
            for (int i = 0; i < timeS.length; i++) {
                timeS[i] = run.secondsOf(samples.timeNs()[i]);
            }
            long fellAtNs = samples.firstTimeAboveNs(RunSummary.FALL_THRESHOLD_RAD);
            int upTo = samples.size();
            if (fellAtNs >= 0) {
                upTo = 0;
                while (upTo < samples.size() && samples.timeNs()[upTo] < fellAtNs) {
                    upTo++;
                }
            }
            List<ControlCycle> cycles = run.cycles().stream()
                    .sorted(Comparator.comparingLong(ControlCycle::releaseNs)).toList();
            // Where Ticks were skipped (no cycle for two periods or more) the line breaks instead of
            // sloping across the gap; the cycle before it holds its value for its period, at least
            // two pixels, so that even a cycle alone between two gaps shows.
            long holdNs = Math.max(run.periodNs(), Math.round(2e9 * endS / StackedChart.PLOT_WIDTH));
            double[][] lateness = new double[2][3 * cycles.size()];
            int n = 0;
            for (int i = 0; i < cycles.size(); i++) {
                long releaseNs = cycles.get(i).releaseNs();
                long gapNs = i == 0 ? 0 : releaseNs - cycles.get(i - 1).releaseNs();
                if (gapNs >= 2 * run.periodNs()) {
                    lateness[0][n] = run.secondsOf(cycles.get(i - 1).releaseNs() + Math.min(holdNs, gapNs / 2));
                    lateness[1][n] = lateness[1][n - 1];
                    n++;
                    lateness[0][n] = lateness[0][n - 1];
                    lateness[1][n++] = Double.NaN;
                }
                lateness[0][n] = run.secondsOf(releaseNs);
                lateness[1][n++] = Math.max(LATENESS_FLOOR_MS, cycles.get(i).startLatenessNs() / 1e6);
            }
            lateness = new double[][] {Arrays.copyOf(lateness[0], n), Arrays.copyOf(lateness[1], n)};
            return new Trace(run, timeS, samples.theta1Rad(), samples.theta2Rad(), samples.torqueNm(), lateness, upTo,
                    fellAtNs >= 0 ? run.secondsOf(fellAtNs) : Double.NaN);
        }

        boolean fell() {
            return !Double.isNaN(fellAtS);
        }

        /**
         * {@code values} up to the first sample past the fall threshold, NaN after it: what the
         * loop does with a fallen pendulum (the arm spinning at full torque) is no longer control.
         */
        double[] untilFallen(double[] values) {
            double[] kept = values.clone();
            Arrays.fill(kept, Math.min(kept.length, upTo + 1), kept.length, Double.NaN);
            return kept;
        }

        double[] values(int panel) {
            return switch (panel) {
                case THETA1 -> theta1Rad;
                case THETA2 -> theta2Rad;
                case TORQUE -> torqueNm;
                default -> throw new IllegalArgumentException("panel=" + panel + " has no sample values");
            };
        }

        /** The largest |value| while the pendulum was up. */
        double maxAbs(int panel) {
            double[] values = values(panel);
            double max = 0.0;
            for (int i = 0; i < upTo; i++) {
                max = Math.max(max, Math.abs(values[i]));
            }
            return max;
        }
    }

    /** θ1 from its smallest to its largest while up, set point included, with a margin. */
    private static double[] theta1Range(List<Trace> traces) {
        double lo = SET_POINT_RAD;
        double hi = SET_POINT_RAD;
        for (Trace trace : traces) {
            for (int i = 0; i < trace.upTo(); i++) {
                lo = Math.min(lo, trace.theta1Rad()[i]);
                hi = Math.max(hi, trace.theta1Rad()[i]);
            }
        }
        lo = Math.max(lo, -MAX_ANGLE_RAD);
        hi = Math.min(hi, MAX_ANGLE_RAD);
        double margin = Math.max(0.005, 0.1 * (hi - lo));
        return new double[] {lo - margin, hi + margin};
    }

    /** ± the largest |value| while up, with a margin, at least ±{@code minimum}, at most ±{@code maximum}. */
    private static double[] symmetric(List<Trace> traces, int panel, double minimum, double maximum) {
        double max = traces.stream().mapToDouble(t -> t.maxAbs(panel)).max().orElse(0.0);
        double top = Math.clamp(1.15 * max, minimum, maximum);
        return new double[] {-top, top};
    }

    /** From half the smallest lateness to twice the largest (and twice one period). */
    private static double[] latenessRange(List<Trace> traces) {
        double max = traces.getFirst().run().periodNs() / 1e6;
        double min = max;
        for (Trace trace : traces) {
            for (double latenessMs : trace.lateness()[1]) {
                if (!Double.isNaN(latenessMs)) {
                    max = Math.max(max, latenessMs);
                    min = Math.min(min, latenessMs);
                }
            }
        }
        return new double[] {Math.max(LATENESS_FLOOR_MS, min / 2), 2 * max};
    }

    /**
     * The dashed references: θ1's set point, θ2's fall threshold and u's torque limit where the
     * scale reaches them, and one control period of lateness (a Tick that starts a period late has
     * missed its deadline). One legend entry names them all.
     */
    private static void references(StackedChart figure, double endS, double[][] ranges, double periodMs) {
        reference(figure.panel(THETA1), "set point", endS, SET_POINT_RAD);
        if (ranges[THETA2][1] >= RunSummary.FALL_THRESHOLD_RAD) {
            reference(figure.panel(THETA2), "fall threshold", endS, RunSummary.FALL_THRESHOLD_RAD,
                    -RunSummary.FALL_THRESHOLD_RAD);
        }
        if (ranges[TORQUE][1] >= TORQUE_LIMIT_NM) {
            reference(figure.panel(TORQUE), "torque limit", endS, TORQUE_LIMIT_NM, -TORQUE_LIMIT_NM);
        }
        XYSeries period = reference(figure.panel(LATENESS), "period", endS, periodMs);
        period.setLabel(String.format(Locale.ROOT, "set point, limits, one period (%s ms)",
                BigDecimal.valueOf(periodMs).stripTrailingZeros().toPlainString()));
        period.setShowInLegend(true);
    }

    private static XYSeries reference(XYChart panel, String name, double endS, double... levels) {
        double[] x = new double[3 * levels.length - 1];
        double[] y = new double[x.length];
        for (int i = 0; i < levels.length; i++) {
            int at = 3 * i;
            x[at] = 0.0;
            x[at + 1] = endS;
            y[at] = levels[i];
            y[at + 1] = levels[i];
            if (at + 2 < x.length) {
                x[at + 2] = endS;
                y[at + 2] = Double.NaN; // a break between the lines
            }
        }
        XYSeries series = line(panel, "reference " + name, x, y, REFERENCE, DASHED);
        series.setShowInLegend(false);
        return series;
    }

    /**
     * One shaded band per stress activation, from its start to its end. XChart fills an area
     * series down to zero (on a log axis, to where it maps zero), so each band is two series, one
     * to the top of the panel and one to its bottom.
     */
    private static void shadeStress(XYChart panel, ScenarioRun run, double lo, double hi, int p) {
        List<double[]> bands = new ArrayList<>();
        long startNs = Long.MIN_VALUE;
        for (ScenarioEvent event : run.events()) {
            if (event.kind() == ScenarioEvent.Kind.STRESS_START) {
                startNs = event.timeNs();
            } else if (event.kind() == ScenarioEvent.Kind.STRESS_END && startNs != Long.MIN_VALUE) {
                bands.add(new double[] {run.secondsOf(startNs), run.secondsOf(event.timeNs())});
                startNs = Long.MIN_VALUE;
            }
        }
        if (startNs != Long.MIN_VALUE) {
            bands.add(new double[] {run.secondsOf(startNs), run.durationS()}); // still computing at the end
        }
        double[] edges = {hi, lo};
        for (int i = 0; i < bands.size(); i++) {
            double[] band = bands.get(i);
            for (int e = 0; e < edges.length; e++) {
                XYSeries series = panel.addSeries("stress " + i + "." + e, band, new double[] {edges[e], edges[e]});
                series.setXYSeriesRenderStyle(XYSeries.XYSeriesRenderStyle.Area);
                series.setMarker(SeriesMarkers.NONE);
                series.setFillColor(STRESS_SHADE);
                series.setLineColor(STRESS_SHADE);
                series.setLabel("stress task running");
                series.setShowInLegend(p == LATENESS && i == 0 && e == 0);
            }
        }
    }

    /** A vertical line at each upgrade or migration request; the legend names the first. */
    private static void markEvents(XYChart panel, List<ScenarioRun> runs, double lo, double hi, int p) {
        int index = 0;
        for (ScenarioRun run : runs) {
            for (ScenarioEvent event : run.events()) {
                String what = switch (event.kind()) {
                    case UPGRADE -> "upgrade";
                    case MIGRATION -> "migration";
                    default -> null;
                };
                if (what == null) {
                    continue;
                }
                double atS = run.secondsOf(event.timeNs());
                XYSeries series = line(panel, "mark " + index, new double[] {atS, atS}, new double[] {lo, hi},
                        MARK, new BasicStroke(1.5f));
                series.setLabel(what + " (management request)");
                series.setShowInLegend(p == LATENESS && index == 0);
                index++;
            }
        }
    }

    /** A line series; {@code name} is its key in the panel, never shown (the legend shows labels). */
    private static XYSeries line(XYChart chart, String name, double[] x, double[] y, Color color,
            BasicStroke stroke) {
        XYSeries series = chart.addSeries(name, x, y);
        series.setXYSeriesRenderStyle(XYSeries.XYSeriesRenderStyle.Line);
        series.setMarker(SeriesMarkers.NONE);
        series.setLineColor(color);
        series.setLineStyle(stroke);
        return series;
    }

    /**
     * {@code values} as a panel from {@code lo} to {@code hi} draws them: a value outside that
     * neighbours one inside is kept (pulled in to just beyond the edge), so the line visibly leaves
     * and re-enters the panel; the values between, all outside, become a break. A fallen pendulum
     * spinning far outside the scale draws nothing then, instead of lines across the panel.
     */
    static double[] leavingThePanel(double[] values, double lo, double hi) {
        double span = hi - lo;
        double[] drawn = new double[values.length];
        for (int i = 0; i < values.length; i++) {
            boolean inside = values[i] >= lo && values[i] <= hi;
            boolean besideInside = (i > 0 && values[i - 1] >= lo && values[i - 1] <= hi)
                    || (i + 1 < values.length && values[i + 1] >= lo && values[i + 1] <= hi);
            drawn[i] = inside ? values[i] : besideInside ? Math.clamp(values[i], lo - span, hi + span) : Double.NaN;
        }
        return drawn;
    }
}
