package io.etherware.examples.scenario;

import static org.junit.jupiter.api.Assertions.assertEquals;
import static org.junit.jupiter.api.Assertions.assertTrue;

import java.io.ByteArrayOutputStream;
import java.io.PrintStream;
import java.nio.charset.StandardCharsets;
import java.util.List;
import org.junit.jupiter.api.Test;

class ProgressTest {

    private final ByteArrayOutputStream bytes = new ByteArrayOutputStream();
    private final PrintStream out = new PrintStream(bytes, true, StandardCharsets.UTF_8);

    @Test
    void shouldPrintALineEveryFewSecondsAndTheLastStateWhenNotOnATerminal() {
        var progress = new Progress("Etherware-RT", 20.0, out, false);
        for (double t = 0.5; t < 20.0; t += 0.5) {
            progress.update(t, 0.001, 0);
        }
        progress.finish(20.0, -0.0021, 3);

        List<String> lines = bytes.toString(StandardCharsets.UTF_8).lines().toList();
        assertEquals(5, lines.size(), lines::toString);
        assertTrue(lines.getFirst().matches("Etherware-RT\\s+0\\.5 / 20\\.0 s\\s+θ2 \\+0\\.0010 rad\\s+misses 0"),
                lines.getFirst());
        assertTrue(lines.getLast().matches("Etherware-RT\\s+20\\.0 / 20\\.0 s\\s+θ2 -0\\.0021 rad\\s+misses 3"),
                lines.getLast());
    }

    @Test
    void shouldRewriteOneLineInPlaceOnATerminal() {
        var progress = new Progress("fifo", 2.0, out, true);
        progress.update(1.0, 0.0, 0);
        progress.finish(2.0, 0.7, 12);

        String text = bytes.toString(StandardCharsets.UTF_8);
        assertEquals(2, text.chars().filter(c -> c == '\r').count(), text);
        assertTrue(text.endsWith(System.lineSeparator()) && text.contains("misses 12"), text);
    }
}
