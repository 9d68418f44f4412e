package io.etherware.examples.deploy;

import static org.junit.jupiter.api.Assertions.assertEquals;
import static org.junit.jupiter.api.Assertions.assertFalse;
import static org.junit.jupiter.api.Assertions.assertTrue;

import io.etherware.examples.scenario.NodeProcess;
import java.nio.file.Files;
import java.nio.file.Path;
import java.util.List;
import java.util.concurrent.TimeUnit;
import java.util.regex.Matcher;
import java.util.regex.Pattern;
import org.junit.jupiter.api.Test;
import org.junit.jupiter.api.condition.EnabledOnOs;
import org.junit.jupiter.api.condition.OS;
import org.junit.jupiter.api.io.TempDir;

/**
 * The pendulum demo as it ships: node 1 ({@code deploy/pendulum-node1.xml}: the simulated board,
 * the DSPProxy and the Notifier) and node 2 ({@code deploy/pendulum-node2.xml}: the controller),
 * each started by the launcher in a JVM of its own and ended with SIGTERM. The pendulum stays up
 * while the loop crosses the two processes, and both nodes close in order.
 */
@EnabledOnOs(OS.LINUX)
class PendulumDeploymentIT {

    /** How long the loop runs, by the plant's own reports. */
    private static final double RUN_S = 8.0;
    private static final Pattern REPORT = Pattern.compile(
            "PLANT seconds=([0-9.]+) theta2=(-?[0-9.]+) maxAbsTheta2=([0-9.]+) fell=(true|false) lateCycles=([0-9]+)");

    @TempDir
    Path dir;

    @Test
    void shouldBalanceThePendulumFromTheTwoShippedDeploymentFiles() throws Exception {
        Path addressFile = dir.resolve("node1.address");
        Path log1 = dir.resolve("node1.log");
        Path log2 = dir.resolve("node2.log");
        List<String> said1;
        List<String> said2;
        int exit1;
        int exit2;
        try (NodeProcess node1 = NodeProcess.start(List.of("node", "-P", "listen=127.0.0.1:0", "--address-file",
                addressFile.toString(), "deploy/pendulum-node1.xml"), log1, 60)) {
            String plant = Files.readString(addressFile).strip();
            try (NodeProcess node2 = NodeProcess.start(List.of("node", "-P", "listen=127.0.0.1:0", "-P",
                    "plant=" + plant, "-P", "view=127.0.0.1:0", "deploy/pendulum-node2.xml"), log2, 60)) {
                // The board starts at the controller's first request; wait for RUN_S of its reports.
                long giveUpNs = System.nanoTime() + TimeUnit.SECONDS.toNanos(60);
                while (reportedSeconds(node1.linesSoFar()) < RUN_S) {
                    assertTrue(System.nanoTime() < giveUpNs, () -> "node 1 did not report " + RUN_S
                            + " s of the plant within 60 s; it said " + node1.linesSoFar() + "; logs in " + dir);
                    Thread.sleep(100);
                }
                said1 = node1.terminate();
                exit1 = node1.exitValue();
                said2 = node2.terminate();
                exit2 = node2.exitValue();
            }
        }
        Matcher last = lastReport(said1);
        System.out.println("node 1: " + String.join(" | ", said1));

        // Upright throughout, with margin (it falls past 0.5 rad within a second without control).
        assertEquals("false", last.group(4), last.group());
        double maxAbsTheta2 = Double.parseDouble(last.group(3));
        assertTrue(maxAbsTheta2 < 0.15, () -> "max |θ2| " + maxAbsTheta2 + " rad: " + last.group());
        // SIGTERM ended both (status 143), each closing in order rather than being killed midway.
        assertEquals(143, exit1, "node 1's exit status");
        assertEquals(143, exit2, "node 2's exit status");
        for (Path log : List.of(log1, log2)) {
            String text = Files.readString(log);
            assertTrue(text.contains("closing") && text.contains(" closed"), () -> log + ":\n" + text);
            assertFalse(text.contains("closed by itself"), () -> log + ":\n" + text);
        }
        System.out.println("node 2: " + String.join(" | ", said2));
        // Node 2 runs the controller and its live view, on loopback, on the free port it was given.
        String node2Log = Files.readString(log2);
        assertTrue(Pattern.compile("view on http://127\\.0\\.0\\.1:[1-9][0-9]*/").matcher(node2Log).find(),
                () -> log2 + ":\n" + node2Log);
    }

    private static double reportedSeconds(List<String> lines) {
        Matcher last = lastReport(lines);
        return last == null ? 0 : Double.parseDouble(last.group(1));
    }

    private static Matcher lastReport(List<String> lines) {
        Matcher found = null;
        for (String line : lines) {
            Matcher matcher = REPORT.matcher(line);
            if (matcher.matches()) {
                found = matcher;
            }
        }
        return found;
    }
}
