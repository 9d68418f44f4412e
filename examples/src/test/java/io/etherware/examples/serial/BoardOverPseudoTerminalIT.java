package io.etherware.examples.serial;

import static org.junit.jupiter.api.Assertions.assertEquals;
import static org.junit.jupiter.api.Assertions.assertTrue;

import io.etherware.examples.scenario.NodeProcess;
import java.nio.file.Files;
import java.nio.file.Path;
import java.util.List;
import org.junit.jupiter.api.Test;
import org.junit.jupiter.api.condition.EnabledOnOs;
import org.junit.jupiter.api.condition.OS;
import org.junit.jupiter.api.io.TempDir;

/**
 * The DSP board simulator as a process of its own ({@code etherware-demo dsp-board}) on a
 * pseudo-terminal, and a node in a second process, started by the launcher from the shipped
 * {@code deploy/pendulum-one-node.xml} with the port named on its command line: its DSPProxy opens
 * the port by name through jSerialComm, as it would open the real board's. The pendulum stays up,
 * by the board's own ground truth.
 */
@EnabledOnOs(OS.LINUX)
class BoardOverPseudoTerminalIT {

    private static final long RUN_MS = 8_000;

    @TempDir
    Path dir;

    @Test
    void shouldKeepThePendulumUpWithBoardAndNodeInTwoProcessesOverAPseudoTerminal() throws Exception {
        Path portFile = dir.resolve("board.port");
        List<String> boardSaid;
        int nodeExit;
        try (NodeProcess board = NodeProcess.start(List.of("dsp-board", "--port-file", portFile.toString(),
                "--start-on-request"), dir.resolve("board.log"), 60)) {
            String port = Files.readString(portFile).strip();
            try (NodeProcess node = NodeProcess.start(List.of("node", "-P", "port=" + port,
                    "deploy/pendulum-one-node.xml"), dir.resolve("node.log"), 60)) {
                Thread.sleep(RUN_MS); // the loop runs in the two processes meanwhile
                boardSaid = board.stop(); // the board first: its summary covers only the controlled run
                node.terminate();
                nodeExit = node.exitValue();
            }
        }
        String summary = boardSaid.stream().filter(line -> line.startsWith(DspBoardCommand.SUMMARY)).findFirst()
                .orElseThrow(() -> new AssertionError("the board printed no summary: " + boardSaid));
        System.out.println("board: " + String.join(" | ", boardSaid));

        // The plant's own ground truth, from the board's process: upright throughout, with margin
        // (uncontrolled, it passes 0.5 rad within a second).
        assertTrue(summary.contains("fell=false"), summary);
        double maxTrue = Double.parseDouble(summary.replaceAll(".*maxAbsTheta2=([0-9.]+).*", "$1"));
        assertTrue(maxTrue < 0.15, () -> "max |θ2| " + maxTrue + " rad: " + summary);
        // The board ran for most of the run: it started at the node's first request.
        double seconds = Double.parseDouble(summary.replaceAll(".*seconds=([0-9.]+).*", "$1"));
        assertTrue(seconds > RUN_MS / 1000.0 / 2, () -> "the board ran " + seconds + " s: " + summary);
        assertEquals(143, nodeExit, "the node's exit status after SIGTERM");
    }
}
