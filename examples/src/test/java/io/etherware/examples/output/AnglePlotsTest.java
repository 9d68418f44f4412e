package io.etherware.examples.output;

import static org.junit.jupiter.api.Assertions.assertEquals;
import static org.junit.jupiter.api.Assertions.assertTrue;

import io.etherware.examples.scenario.Runs;
import io.etherware.examples.scenario.ScenarioEvent;
import io.etherware.examples.scenario.ScenarioRun;
import java.awt.image.BufferedImage;
import java.nio.file.Files;
import java.nio.file.Path;
import java.util.List;
import javax.imageio.ImageIO;
import org.junit.jupiter.api.BeforeAll;
import org.junit.jupiter.api.Test;
import org.junit.jupiter.api.io.TempDir;

class AnglePlotsTest {

    @BeforeAll
    static void headless() {
        System.setProperty("java.awt.headless", "true");
    }

    @Test
    void shouldSaveAPngOfTheReadmeSizeAndAnSvgOfTheSameChart(@TempDir Path dir) throws Exception {
        double[] theta2 = new double[200];
        for (int i = 0; i < theta2.length; i++) {
            theta2[i] = i < 100 ? 0.01 * Math.sin(i / 5.0) : 0.01 * Math.exp((i - 100) / 10.0);
        }
        long p = Runs.PERIOD_NS;
        ScenarioRun fifo = Runs.run("fifo", Runs.samples(theta2), List.of(),
                List.of(new ScenarioEvent(50 * p, ScenarioEvent.Kind.STRESS_START, "stress 1 start"),
                        new ScenarioEvent(110 * p, ScenarioEvent.Kind.STRESS_END, "stress 1 end"),
                        new ScenarioEvent(190 * p, ScenarioEvent.Kind.STRESS_START, "stress 2 start")), 200 * p);
        ScenarioRun rt = Runs.run("rt", Runs.samples(new double[200]), List.of(), fifo.events(), 200 * p);

        List<Path> files = AnglePlots.save(AnglePlots.compareTheta2(List.of(fifo, rt), "θ2 under stress"),
                dir.resolve("stress"));
        List<Path> single = AnglePlots.save(AnglePlots.jointAngles(fifo, "joint angles"), dir.resolve("fifo"));

        assertEquals(List.of(dir.resolve("stress.png"), dir.resolve("stress.svg")), files);
        BufferedImage png = ImageIO.read(files.get(0).toFile());
        assertEquals(AnglePlots.WIDTH, png.getWidth());
        assertEquals(AnglePlots.HEIGHT, png.getHeight());
        String svg = Files.readString(files.get(1));
        assertTrue(svg.contains("<svg") && svg.contains("viewBox=\"0 0 800 400\""), "an 800x400 SVG");
        assertTrue(Files.size(single.get(0)) > 1_000, "the single-run PNG has content");
    }
}
