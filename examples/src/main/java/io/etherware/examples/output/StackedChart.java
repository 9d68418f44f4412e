package io.etherware.examples.output;

import java.awt.BasicStroke;
import java.awt.Color;
import java.awt.Font;
import java.awt.Graphics2D;
import java.awt.image.BufferedImage;
import java.io.IOException;
import java.nio.charset.StandardCharsets;
import java.nio.file.Files;
import java.nio.file.Path;
import java.util.ArrayList;
import java.util.List;
import javax.imageio.ImageIO;
import org.knowm.xchart.XYChart;
import org.knowm.xchart.style.Styler;
import org.knowm.xchart.style.XYStyler;

/**
 * XChart panels stacked on one time axis, as an oscilloscope or a Simulink scope shows signals:
 * the same x range and plot width in every panel, the title above the first, the time axis and the
 * legend below the last. Saved as one PNG and one SVG.
 *
 * <p>The SVG is kept small: points are thinned before they reach a panel ({@link Decimation}) and
 * the SVG is written compactly ({@link CompactSvg}).
 *
 * <p>Not thread-safe: built, filled and saved on one thread.
 */
public final class StackedChart {

    /** Width of the figure, px: the README's. */
    public static final int WIDTH = 800;
    /** Width of each panel's plot area, px (the figure less its y axis and padding): a column per pixel for thinning. */
    public static final int PLOT_WIDTH = 715;
    /** Height of each panel's plot area, px. */
    public static final int PLOT_HEIGHT = 105;
    /** Width kept for the y axis of every panel (ticks and title), px, so the plots line up. */
    private static final int Y_AXIS_WIDTH = 78;
    private static final int TITLE_HEIGHT = 26;
    private static final int TIME_AXIS_HEIGHT = 38;
    private static final int LEGEND_HEIGHT = 34;
    private static final int PADDING = 6;

    private final List<XYChart> panels = new ArrayList<>();
    private final int height;

    /**
     * {@code yTitles.size()} empty panels, top to bottom, over time from {@code startS} to
     * {@code endS}; {@code title} goes above the first.
     */
    public StackedChart(String title, List<String> yTitles, double startS, double endS) {
        if (yTitles.isEmpty()) {
            throw new IllegalArgumentException("yTitles is empty: a figure needs at least one panel");
        }
        int total = 0;
        for (int i = 0; i < yTitles.size(); i++) {
            boolean first = i == 0;
            boolean last = i == yTitles.size() - 1;
            int panelHeight = PLOT_HEIGHT + 2 * PADDING + (first ? TITLE_HEIGHT : 0)
                    + (last ? TIME_AXIS_HEIGHT + LEGEND_HEIGHT : 0);
            XYChart chart = new XYChart(WIDTH, panelHeight);
            style(chart, yTitles.get(i), startS, endS);
            chart.setTitle(first ? title : "");
            chart.getStyler().setChartTitleVisible(first);
            chart.getStyler().setLegendVisible(last);
            if (!last) {
                // Tick labels and title of the shared time axis only below the last panel.
                chart.getStyler().setXAxisTicksVisible(false);
                chart.getStyler().setXAxisTitleVisible(false);
            }
            panels.add(chart);
            total += panelHeight;
        }
        this.height = total;
    }

    /** Panel {@code index}, 0 at the top, for its series and range. */
    public XYChart panel(int index) {
        return panels.get(index);
    }

    /** The number of panels. */
    public int panelCount() {
        return panels.size();
    }

    /** The figure's height in pixels. */
    public int height() {
        return height;
    }

    /** The figure as an image. */
    public BufferedImage toImage() {
        BufferedImage image = new BufferedImage(WIDTH, height, BufferedImage.TYPE_INT_RGB);
        Graphics2D g = image.createGraphics();
        try {
            paint(g);
        } finally {
            g.dispose();
        }
        return image;
    }

    /** The figure as an SVG document, written compactly ({@link CompactSvg}). */
    public String toSvg() throws IOException {
        return CompactSvg.of(this::paint, WIDTH, height);
    }

    /** Saves the figure as {@code <base>.png} and {@code <base>.svg}; returns both paths. */
    public List<Path> save(Path base) throws IOException {
        Path png = base.resolveSibling(base.getFileName() + ".png");
        Path svg = base.resolveSibling(base.getFileName() + ".svg");
        if (!ImageIO.write(toImage(), "png", png.toFile())) {
            throw new IOException("no PNG writer in this JDK for " + png);
        }
        Files.writeString(svg, toSvg(), StandardCharsets.UTF_8);
        return List.of(png, svg);
    }

    private void paint(Graphics2D g) {
        int y = 0;
        for (XYChart chart : panels) {
            Graphics2D panel = (Graphics2D) g.create(0, y, WIDTH, chart.getHeight());
            try {
                chart.paint(panel, WIDTH, chart.getHeight());
            } finally {
                panel.dispose();
            }
            y += chart.getHeight();
        }
    }

    private static void style(XYChart chart, String yTitle, double startS, double endS) {
        chart.setXAxisTitle("time (s)");
        chart.setYAxisTitle(yTitle);
        XYStyler styler = chart.getStyler();
        styler.setLegendPosition(Styler.LegendPosition.OutsideS)
                .setLegendLayout(Styler.LegendLayout.Horizontal)
                .setLegendFont(new Font(Font.SANS_SERIF, Font.PLAIN, 11))
                .setLegendPadding(4)
                .setChartBackgroundColor(Color.WHITE)
                .setPlotBackgroundColor(Color.WHITE)
                .setChartPadding(PADDING)
                .setChartTitleFont(new Font(Font.SANS_SERIF, Font.BOLD, 14))
                .setAntiAlias(true);
        styler.setAxisTitleFont(new Font(Font.SANS_SERIF, Font.PLAIN, 11));
        styler.setAxisTickLabelsFont(new Font(Font.SANS_SERIF, Font.PLAIN, 10));
        styler.setPlotMargin(0);
        styler.setPlotContentSize(1.0); // the ranges are set to the data with margins of their own
        styler.setYAxisLeftWidthHint(Y_AXIS_WIDTH);
        styler.setPlotGridLinesColor(new Color(230, 230, 230));
        styler.setPlotGridLinesStroke(new BasicStroke(1.0f)); // solid: a dashed line is written as many shapes
        styler.setXAxisMin(startS);
        styler.setXAxisMax(endS);
        styler.setXAxisDecimalPattern("0.#");
    }
}
