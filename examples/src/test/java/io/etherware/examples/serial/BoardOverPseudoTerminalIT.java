package io.etherware.examples.serial;

import static org.junit.jupiter.api.Assertions.assertTrue;

import io.etherware.core.kernel.EtherwareNode;
import io.etherware.core.message.ContentsTypes;
import io.etherware.core.message.Criticality;
import io.etherware.core.time.NodeClock;
import io.etherware.examples.scenario.NodeProcess;
import io.etherware.examples.scenario.PendulumRig;
import io.etherware.examples.scenario.PlantWiring;
import io.etherware.examples.scenario.Schedulers;
import io.etherware.pendulum.components.ControlCycle;
import io.etherware.pendulum.components.ControllerConfig;
import io.etherware.pendulum.components.DspProxy;
import io.etherware.pendulum.components.PendulumContents;
import io.etherware.pendulum.components.PendulumController;
import io.etherware.pendulum.control.GainSet;
import io.etherware.pendulum.serial.DspClient;
import io.etherware.pendulum.serial.JSerialCommLink;
import io.etherware.services.notifier.Notifier;
import io.etherware.services.notifier.NotifierConfig;
import io.etherware.services.notifier.Subscription;
import java.nio.file.Files;
import java.nio.file.Path;
import java.util.List;
import java.util.concurrent.CopyOnWriteArrayList;
import java.util.concurrent.TimeUnit;
import org.junit.jupiter.api.Test;
import org.junit.jupiter.api.condition.EnabledOnOs;
import org.junit.jupiter.api.condition.OS;
import org.junit.jupiter.api.io.TempDir;

/**
 * The DSP board simulator as a process of its own ({@code etherware-demo dsp-board}) on a
 * pseudo-terminal, and a node in this JVM whose DSPProxy opens the port by name through
 * jSerialComm, as it would open the real board's: the pendulum stays up.
 */
@EnabledOnOs(OS.LINUX)
class BoardOverPseudoTerminalIT {

    private static final long PERIOD_NS = TimeUnit.MILLISECONDS.toNanos(15);
    private static final long RUN_MS = 8_000;

    @TempDir
    Path dir;

    @Test
    void shouldKeepThePendulumUpWithTheBoardInAnotherProcessBehindAPseudoTerminal() throws Exception {
        Path portFile = dir.resolve("board.port");
        var cycles = new CopyOnWriteArrayList<ControlCycle>();
        List<String> boardSaid;
        try (NodeProcess board = NodeProcess.start(List.of("dsp-board", "--port-file", portFile.toString()),
                dir.resolve("board.log"), 60)) {
            String port = Files.readString(portFile).strip();
            var wiring = new PlantWiring(PlantWiring.DEFAULT_BAUD_RATE);
            NodeClock clock = NodeClock.system();
            try (JSerialCommLink link = JSerialCommLink.open(port, wiring.baudRate());
                 EtherwareNode node = EtherwareNode.builder().nodeId("pty-node").scheduler(Schedulers::etherwareRt)
                         .clock(clock).contentsTypes(PendulumContents.register(new ContentsTypes())).build()) {
                node.add(DspProxy.DEFAULT_PROFILE, DspProxy.factory(new DspClient(link, clock, wiring.client())));
                node.add(PendulumController.DEFAULT_PROFILE, PendulumController.factory(ControllerConfig.defaults(),
                        GainSet.v1Soft(PendulumRig.PARAMETERS), cycles::add));
                node.start();
                Notifier notifier = Notifier.install(node, NotifierConfig.defaults());
                board.send("START"); // the pendulum starts to fall now
                notifier.subscribe(Subscription.periodic("controller", PendulumController.DEFAULT_PROFILE,
                        Criticality.HIGH, PERIOD_NS));
                Thread.sleep(RUN_MS); // the loop runs on the node's threads meanwhile
                notifier.unsubscribe("controller");
            }
            boardSaid = board.stop();
        }
        String summary = boardSaid.stream().filter(line -> line.startsWith(DspBoardCommand.SUMMARY)).findFirst()
                .orElseThrow(() -> new AssertionError("the board printed no summary: " + boardSaid));
        System.out.println("board: " + String.join(" | ", boardSaid));
        long commanded = cycles.stream().filter(c -> c.outcome() == ControlCycle.Outcome.COMMANDED).count();
        double maxRead = cycles.stream().filter(c -> c.outcome() == ControlCycle.Outcome.COMMANDED)
                .mapToDouble(c -> Math.abs(c.theta2Rad())).max().orElse(Double.NaN);
        System.out.printf("node: %d cycles, %d commanded, max |θ2| read %.4f rad%n", cycles.size(), commanded,
                maxRead);

        // The plant's own ground truth, from the board's process: upright throughout, with margin.
        assertTrue(summary.contains("fell=false"), summary);
        double maxTrue = Double.parseDouble(summary.replaceAll(".*maxAbsTheta2=([0-9.]+).*", "$1"));
        assertTrue(maxTrue < 0.15, () -> "max |θ2| " + maxTrue + " rad: " + summary);
        // The loop ran across the process boundary: most of the ~530 periods ended in a command.
        assertTrue(commanded > RUN_MS * 1_000_000 / PERIOD_NS / 2, () -> commanded + " commanded cycles of "
                + cycles.size());
    }
}
