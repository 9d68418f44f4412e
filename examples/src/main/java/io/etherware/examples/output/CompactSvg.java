package io.etherware.examples.output;

import de.erichseifert.vectorgraphics2d.Document;
import de.erichseifert.vectorgraphics2d.VectorGraphics2D;
import de.erichseifert.vectorgraphics2d.intermediate.CommandSequence;
import de.erichseifert.vectorgraphics2d.intermediate.MutableCommandSequence;
import de.erichseifert.vectorgraphics2d.intermediate.commands.Command;
import de.erichseifert.vectorgraphics2d.intermediate.commands.DrawShapeCommand;
import de.erichseifert.vectorgraphics2d.intermediate.commands.SetColorCommand;
import de.erichseifert.vectorgraphics2d.intermediate.commands.SetStrokeCommand;
import de.erichseifert.vectorgraphics2d.svg.SVGProcessor;
import de.erichseifert.vectorgraphics2d.util.PageSize;
import java.awt.Graphics2D;
import java.awt.geom.Line2D;
import java.awt.geom.Path2D;
import java.io.ByteArrayOutputStream;
import java.io.IOException;
import java.nio.charset.StandardCharsets;
import java.util.ArrayList;
import java.util.List;
import java.util.Objects;
import java.util.function.Consumer;
import java.util.regex.Matcher;
import java.util.regex.Pattern;

/**
 * Writes what XChart paints as a compact SVG, with XChart's own SVG writer (VectorGraphics2D).
 * XChart draws a line as one segment per point, which that writer turns into one
 * {@code <line>} element each, about 200 bytes with its style: a minute at 15 ms in four panels
 * made 1 to 2 MB. Here consecutive segments of one colour and stroke become one path, polylines
 * are written in relative coordinates, and every coordinate keeps one decimal (a tenth of a
 * pixel; text comes as glyph outlines, so numbers are most of the file).
 *
 * <p>Stateless and thread-safe.
 */
final class CompactSvg {

    /** A path of moves and lines only, as the joined lines and the axes are. */
    private static final Pattern POLYLINE = Pattern.compile("d=\"(M[-0-9., ML]*)\"");
    private static final Pattern POINT = Pattern.compile("([ML])(-?[0-9.]+),(-?[0-9.]+)");
    private static final Pattern LONG_DECIMALS = Pattern.compile("(\\.\\d)\\d+");

    private CompactSvg() {
    }

    /** The SVG of what {@code painter} draws on a page of {@code width} × {@code height} px. */
    static String of(Consumer<Graphics2D> painter, int width, int height) throws IOException {
        VectorGraphics2D g = new VectorGraphics2D();
        painter.accept(g);
        Document document = new SVGProcessor().getDocument(joinLines(g.getCommands()),
                new PageSize(0.0, 0.0, width, height));
        var bytes = new ByteArrayOutputStream();
        document.writeTo(bytes);
        return shortDecimals(relativePolylines(bytes.toString(StandardCharsets.UTF_8)));
    }

    /**
     * {@code commands} with each run of line segments drawn in one colour and stroke as one path.
     * Between two segments XChart sets the colour and stroke again (and the marker colour, even
     * without markers); a run goes on as long as those leave the colour and stroke the run started
     * with. Any other command ends the run and is kept, as is every state change that matters.
     */
    static CommandSequence joinLines(CommandSequence commands) {
        var joined = new MutableCommandSequence();
        List<Command<?>> pending = new ArrayList<>(); // colour and stroke changes since the last drawing
        Path2D.Double path = null;
        Object pathColor = null;
        Object pathStroke = null;
        double endX = Double.NaN;
        double endY = Double.NaN;
        for (Command<?> command : commands) {
            if (command instanceof SetColorCommand || command instanceof SetStrokeCommand) {
                pending.add(command);
                continue;
            }
            if (command instanceof DrawShapeCommand && command.getValue() instanceof Line2D line) {
                if (path != null && Objects.equals(last(pending, SetColorCommand.class, pathColor), pathColor)
                        && Objects.equals(last(pending, SetStrokeCommand.class, pathStroke), pathStroke)) {
                    pending.clear();
                    if (line.getX1() != endX || line.getY1() != endY) {
                        path.moveTo(line.getX1(), line.getY1());
                    }
                } else {
                    // Set here, or left by the run before; unknown (null) after any other command.
                    pathColor = last(pending, SetColorCommand.class, path == null ? null : pathColor);
                    pathStroke = last(pending, SetStrokeCommand.class, path == null ? null : pathStroke);
                    flush(joined, path, pending);
                    path = new Path2D.Double();
                    path.moveTo(line.getX1(), line.getY1());
                }
                path.lineTo(line.getX2(), line.getY2());
                endX = line.getX2();
                endY = line.getY2();
                continue;
            }
            flush(joined, path, pending);
            path = null;
            joined.add(command);
        }
        flush(joined, path, pending);
        return joined;
    }

    /** The value of the last command of {@code type} in {@code commands}, or {@code otherwise}. */
    private static Object last(List<Command<?>> commands, Class<?> type, Object otherwise) {
        for (int i = commands.size() - 1; i >= 0; i--) {
            if (type.isInstance(commands.get(i))) {
                return commands.get(i).getValue();
            }
        }
        return otherwise;
    }

    /** Adds {@code path} (if any), then the {@code pending} state changes, to {@code joined}. */
    private static void flush(MutableCommandSequence joined, Path2D path, List<Command<?>> pending) {
        if (path != null) {
            joined.add(new DrawShapeCommand(path));
        }
        pending.forEach(joined::add);
        pending.clear();
    }

    /**
     * {@code svg} with each path of moves and lines written from its first point on in relative
     * steps ({@code l.5,-1.2 .5,.3}), in tenths of a pixel: the steps are taken between
     * positions rounded to a tenth, so they add up to them exactly.
     */
    static String relativePolylines(String svg) {
        Matcher path = POLYLINE.matcher(svg);
        var out = new StringBuilder(svg.length() / 2);
        while (path.find()) {
            path.appendReplacement(out, "");
            out.append("d=\"");
            Matcher point = POINT.matcher(path.group(1));
            long x = 0;
            long y = 0;
            char last = ' ';
            boolean first = true;
            while (point.find()) {
                long nextX = tenths(point.group(2));
                long nextY = tenths(point.group(3));
                char command = first ? 'M' : point.group(1).equals("M") ? 'm' : 'l';
                if (command != last) {
                    out.append(command);
                } else {
                    out.append(' ');
                }
                out.append(first ? decimal(nextX) : decimal(nextX - x)).append(',')
                        .append(first ? decimal(nextY) : decimal(nextY - y));
                x = nextX;
                y = nextY;
                last = command;
                first = false;
            }
            out.append('"');
        }
        path.appendTail(out);
        return out.toString();
    }

    /** {@code svg} with every number cut to one decimal. */
    static String shortDecimals(String svg) {
        return LONG_DECIMALS.matcher(svg).replaceAll("$1");
    }

    private static long tenths(String number) {
        return Math.round(Double.parseDouble(number) * 10);
    }

    /** Tenths as an SVG number: {@code 12} is {@code 1.2}, {@code -3} is {@code -.3}, {@code 20} is {@code 2}. */
    private static String decimal(long tenths) {
        long whole = Math.abs(tenths) / 10;
        long tenth = Math.abs(tenths) % 10;
        return (tenths < 0 ? "-" : "") + (whole == 0 && tenth != 0 ? "" : Long.toString(whole))
                + (tenth == 0 ? "" : "." + tenth);
    }
}
