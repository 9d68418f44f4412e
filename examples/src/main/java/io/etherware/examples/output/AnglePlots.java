package io.etherware.examples.output;

import io.etherware.examples.scenario.ProbeSamples;
import io.etherware.examples.scenario.RunSummary;
import io.etherware.examples.scenario.ScenarioEvent;
import io.etherware.examples.scenario.ScenarioRun;
import java.awt.BasicStroke;
import java.awt.Color;
import java.io.IOException;
import java.nio.file.Path;
import java.util.ArrayList;
import java.util.List;
import org.knowm.xchart.BitmapEncoder;
import org.knowm.xchart.VectorGraphicsEncoder;
import org.knowm.xchart.XYChart;
import org.knowm.xchart.XYSeries;
import org.knowm.xchart.style.Styler;
import org.knowm.xchart.style.XYStyler;
import org.knowm.xchart.style.markers.SeriesMarkers;

/**
 * The scenarios' plots, in the spirit of the paper's Fig. 9 and 11: joint angles against time,
 * with the stress activations shaded, upgrades marked and the fall threshold drawn. Saved as PNG (for the README) and SVG
 * (for print) with XChart.
 *
 * <p>Stateless and thread-safe; charts are built and encoded headless (set
 * {@code java.awt.headless=true} before the first one).
 */
public final class AnglePlots {

    /** The README's size: small enough to sit inline, wide enough for a 20 s trace. */
    public static final int WIDTH = 800;
    public static final int HEIGHT = 400;

    /** The largest angle a plot shows: a turn and a half. */
    private static final double MAX_ANGLE_RAD = 3 * Math.PI;
    private static final Color STRESS_SHADE = new Color(255, 170, 0, 70);
    private static final Color THRESHOLD = new Color(150, 150, 150);
    private static final Color UPGRADE_MARK = new Color(40, 150, 60);
    private static final Color[] RUN_COLORS = {new Color(200, 40, 40), new Color(30, 90, 200),
        new Color(40, 150, 60), new Color(120, 60, 160)};
    private static final BasicStroke DASHED = new BasicStroke(1.0f, BasicStroke.CAP_BUTT, BasicStroke.JOIN_MITER,
            10.0f, new float[] {6.0f, 4.0f}, 0.0f);

    private AnglePlots() {
    }

    /**
     * θ1 and θ2 of one run against time, stress activations shaded, upgrades marked, on a scale
     * that shows the fall threshold.
     */
    public static XYChart jointAngles(ScenarioRun run, String title) {
        return jointAngles(run, title, 0.6);
    }

    /**
     * θ1 and θ2 of one run against time, on a scale of at least ±{@code minRangeRad} (the fall
     * threshold is drawn when the scale reaches it).
     */
    public static XYChart jointAngles(ScenarioRun run, String title, double minRangeRad) {
        XYChart chart = baseChart(title);
        ProbeSamples samples = run.samples();
        double[] timeS = seconds(run, samples.timeNs());
        // Up to one turn each way: beyond it (a fallen pendulum, an arm spinning at full torque)
        // the lines leave the plot, and small angles stay readable.
        double top = Math.min(MAX_ANGLE_RAD,
                Math.max(minRangeRad, 1.1 * Math.max(maxAbs(samples.theta1Rad()), samples.maxAbsTheta2Rad())));
        shadeStress(chart, run, top);
        markUpgrades(chart, run, top);
        line(chart, "θ1 arm (rad)", timeS, clip(samples.theta1Rad(), 2 * top), new Color(120, 120, 120));
        line(chart, "θ2 pendulum (rad)", timeS, clip(samples.theta2Rad(), 2 * top), RUN_COLORS[1]);
        if (top >= RunSummary.FALL_THRESHOLD_RAD) {
            thresholds(chart, run.durationS());
        }
        chart.getStyler().setYAxisMin(-top).setYAxisMax(top);
        return chart;
    }

    /**
     * θ2 of several runs of the same scenario on one set of axes, clipped to ±0.6 rad so a fall
     * leaves the plot while small angles stay readable; stress shaded from the first run.
     */
    public static XYChart compareTheta2(List<ScenarioRun> runs, String title) {
        XYChart chart = baseChart(title);
        double limitRad = 0.6;
        if (!runs.isEmpty()) {
            shadeStress(chart, runs.getFirst(), limitRad);
        }
        for (int i = 0; i < runs.size(); i++) {
            ScenarioRun run = runs.get(i);
            double[] clipped = clip(run.samples().theta2Rad(), 2 * limitRad);
            line(chart, "θ2, " + run.title(), seconds(run, run.samples().timeNs()), clipped,
                    RUN_COLORS[i % RUN_COLORS.length]);
        }
        thresholds(chart, runs.stream().mapToDouble(ScenarioRun::durationS).max().orElse(1.0));
        chart.getStyler().setYAxisMin(-limitRad).setYAxisMax(limitRad);
        return chart;
    }

    /** Saves {@code chart} as {@code <base>.png} and {@code <base>.svg}; returns both paths. */
    public static List<Path> save(XYChart chart, Path base) throws IOException {
        String name = base.toString();
        BitmapEncoder.saveBitmap(chart, name, BitmapEncoder.BitmapFormat.PNG);
        VectorGraphicsEncoder.saveVectorGraphic(chart, name, VectorGraphicsEncoder.VectorGraphicsFormat.SVG);
        return List.of(Path.of(name + ".png"), Path.of(name + ".svg"));
    }

    private static XYChart baseChart(String title) {
        XYChart chart = new XYChart(WIDTH, HEIGHT);
        chart.setTitle(title);
        chart.setXAxisTitle("time (s)");
        chart.setYAxisTitle("angle (rad)");
        XYStyler styler = chart.getStyler();
        styler.setLegendPosition(Styler.LegendPosition.OutsideS)
                .setLegendLayout(Styler.LegendLayout.Horizontal)
                .setChartBackgroundColor(Color.WHITE)
                .setPlotBackgroundColor(Color.WHITE)
                .setAntiAlias(true);
        styler.setPlotGridLinesColor(new Color(230, 230, 230));
        styler.setXAxisMin(0.0);
        styler.setXAxisDecimalPattern("0.#");
        styler.setYAxisDecimalPattern("0.0#");
        return chart;
    }

    private static XYSeries line(XYChart chart, String name, double[] x, double[] y, Color color) {
        XYSeries series = chart.addSeries(name, x, y);
        series.setXYSeriesRenderStyle(XYSeries.XYSeriesRenderStyle.Line);
        series.setMarker(SeriesMarkers.NONE);
        series.setLineColor(color);
        series.setLineStyle(new BasicStroke(1.2f));
        return series;
    }

    /** Dashed lines at ±0.5 rad: beyond them the pendulum counts as fallen. */
    private static void thresholds(XYChart chart, double endS) {
        double limit = RunSummary.FALL_THRESHOLD_RAD;
        XYSeries series = chart.addSeries("fall threshold ±" + limit + " rad", new double[] {0.0, endS, Double.NaN,
            0.0, endS}, new double[] {limit, limit, Double.NaN, -limit, -limit});
        series.setXYSeriesRenderStyle(XYSeries.XYSeriesRenderStyle.Line);
        series.setMarker(SeriesMarkers.NONE);
        series.setLineColor(THRESHOLD);
        series.setLineStyle(DASHED);
    }

    /**
     * One shaded band per stress activation, from its start to its end. XChart fills an area
     * series down to zero, so each band is two series, one above and one below the axis.
     */
    private static void shadeStress(XYChart chart, ScenarioRun run, double heightRad) {
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
        for (int i = 0; i < bands.size(); i++) {
            double[] band = bands.get(i);
            for (double sign : new double[] {1.0, -1.0}) {
                String name = i == 0 && sign > 0 ? "stress task running" : "stress " + (i + 1) + (sign > 0 ? "+" : "-");
                XYSeries series = chart.addSeries(name, band, new double[] {sign * heightRad, sign * heightRad});
                series.setXYSeriesRenderStyle(XYSeries.XYSeriesRenderStyle.Area);
                series.setMarker(SeriesMarkers.NONE);
                series.setFillColor(STRESS_SHADE);
                series.setLineColor(STRESS_SHADE);
                series.setShowInLegend(name.equals("stress task running"));
            }
        }
    }

    /** A vertical line at each upgrade or migration request; the legend names the first. */
    private static void markUpgrades(XYChart chart, ScenarioRun run, double heightRad) {
        int index = 0;
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
            String name = index == 0 ? what + " (management request)" : what + " " + index;
            XYSeries series = chart.addSeries(name, new double[] {atS, atS}, new double[] {-heightRad, heightRad});
            series.setXYSeriesRenderStyle(XYSeries.XYSeriesRenderStyle.Line);
            series.setMarker(SeriesMarkers.NONE);
            series.setLineColor(UPGRADE_MARK);
            series.setLineStyle(new BasicStroke(1.5f));
            series.setShowInLegend(index == 0);
            index++;
        }
    }

    private static double[] seconds(ScenarioRun run, long[] timeNs) {
        double[] seconds = new double[timeNs.length];
        for (int i = 0; i < timeNs.length; i++) {
            seconds[i] = run.secondsOf(timeNs[i]);
        }
        return seconds;
    }

    private static double[] clip(double[] values, double limit) {
        double[] clipped = new double[values.length];
        for (int i = 0; i < values.length; i++) {
            clipped[i] = Math.clamp(values[i], -limit, limit);
        }
        return clipped;
    }

    private static double maxAbs(double[] values) {
        double max = 0.0;
        for (double value : values) {
            max = Math.max(max, Math.abs(value));
        }
        return max;
    }
}
