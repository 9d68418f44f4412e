package io.etherware.examples.output;

import static org.junit.jupiter.api.Assertions.assertEquals;
import static org.junit.jupiter.api.Assertions.assertInstanceOf;

import de.erichseifert.vectorgraphics2d.VectorGraphics2D;
import de.erichseifert.vectorgraphics2d.intermediate.commands.Command;
import de.erichseifert.vectorgraphics2d.intermediate.commands.DrawShapeCommand;
import java.awt.BasicStroke;
import java.awt.Color;
import java.awt.geom.Line2D;
import java.awt.geom.Path2D;
import java.awt.geom.PathIterator;
import java.util.ArrayList;
import java.util.List;
import org.junit.jupiter.api.Test;

class CompactSvgTest {

    @Test
    void shouldJoinSegmentsDrawnAsXChartDrawsThemIntoOnePathPerColour() {
        VectorGraphics2D g = new VectorGraphics2D();
        var stroke = new BasicStroke(1.0f);
        for (int i = 0; i < 3; i++) { // colour, marker colour, stroke, segment: XChart's order per point
            g.setColor(Color.BLUE);
            g.setColor(Color.ORANGE);
            g.setColor(Color.BLUE);
            g.setStroke(stroke);
            g.draw(new Line2D.Double(i, i, i + 1, i + 1));
        }
        g.setColor(Color.RED);
        g.draw(new Line2D.Double(5, 5, 6, 4));

        List<Command<?>> joined = new ArrayList<>();
        CompactSvg.joinLines(g.getCommands()).forEach(joined::add);

        List<Object> drawn = joined.stream().filter(DrawShapeCommand.class::isInstance).map(Command::getValue)
                .map(Object.class::cast).toList();
        assertEquals(2, drawn.size(), joined.toString());
        assertEquals(List.of("M0,0", "L1,1", "L2,2", "L3,3"), segments((Path2D) drawn.get(0)));
        assertEquals(List.of("M5,5", "L6,4"), segments((Path2D) drawn.get(1)));
        assertInstanceOf(Path2D.class, drawn.get(1));
    }

    @Test
    void shouldWriteAPolylineInRelativeTenthsThatAddUpToTheRoundedPoints() {
        String svg = "<path d=\"M10.04,20.0 L10.55,19.96 L12.0,21.26 M0.0,0.0 L-1.0,0.5\" style=\"a\"/>"
                + "<path d=\"M1.26,2 Q3.333,4 5,6 Z\"/>";

        String compact = CompactSvg.shortDecimals(CompactSvg.relativePolylines(svg));

        assertEquals("<path d=\"M10,20l.6,0 1.4,1.3m-12,-21.3l-1,.5\" style=\"a\"/><path d=\"M1.2,2 Q3.3,4 5,6 Z\"/>",
                compact);
    }

    private static List<String> segments(Path2D path) {
        List<String> segments = new ArrayList<>();
        double[] c = new double[6];
        for (PathIterator it = path.getPathIterator(null); !it.isDone(); it.next()) {
            int type = it.currentSegment(c);
            segments.add((type == PathIterator.SEG_MOVETO ? "M" : "L") + (int) c[0] + "," + (int) c[1]);
        }
        return segments;
    }
}
