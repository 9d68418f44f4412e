package io.etherware.examples.deploy;

import io.etherware.core.component.Component;
import io.etherware.core.message.ContentsTypes;
import io.etherware.core.time.NodeClock;
import io.etherware.deploy.ComponentFactory;
import io.etherware.deploy.DeploymentException;
import io.etherware.deploy.Settings;
import io.etherware.examples.scenario.PlantWiring;
import io.etherware.pendulum.components.DspProxy;
import io.etherware.pendulum.components.PendulumContents;
import io.etherware.pendulum.serial.DspClient;
import io.etherware.pendulum.serial.JSerialCommLink;
import io.etherware.pendulum.serial.SerialLink;
import java.io.IOException;
import java.time.Duration;
import java.util.function.Supplier;

/**
 * The pendulum's {@link DspProxy} in a deployment file, on a serial port named in the file, or on
 * a board simulated in the node's own process. Settings, all optional:
 * <ul>
 *   <li>{@code port}: {@code simulated} (default) for the simulated board and pendulum of the
 *       scenarios ({@link SimulatedPlant}), or the port to open through jSerialComm: the real
 *       board's ({@code /dev/ttyUSB0}), or the pseudo-terminal that {@code etherware-demo
 *       dsp-board} prints;</li>
 *   <li>{@code baud}: the line rate, 115200 by default (the paper's RS-232C); with the simulated
 *       board its cycle and the proxy's reply timeout scale with it ({@link PlantWiring});</li>
 *   <li>{@code theta2}: the simulated pendulum's initial angle off upright, in rad (default 0.02);</li>
 *   <li>{@code report}: how often the simulated plant prints its ground truth (default 1s).</li>
 * </ul>
 * The simulated pendulum is held upright until the proxy first speaks to the board, as a hand lets
 * go when the control loop starts, so a controller on a node that starts later is not too late.
 */
public final class DspProxyFactory implements ComponentFactory {

    /** The {@code port} value that simulates the board in this process. */
    public static final String SIMULATED = "simulated";

    /** Made by the launcher. */
    public DspProxyFactory() {
    }

    @Override
    public void registerContents(ContentsTypes types) {
        PendulumContents.register(types);
    }

    @Override
    public Supplier<? extends Component> create(Settings settings, Resources resources) throws DeploymentException {
        String port = settings.string("port", SIMULATED);
        int baud = (int) settings.integer("baud", PlantWiring.DEFAULT_BAUD_RATE, PlantWiring.MIN_BAUD_RATE,
                PlantWiring.MAX_BAUD_RATE);
        double theta2 = settings.number("theta2", 0.02, -0.3, 0.3);
        Duration report = settings.duration("report", Duration.ofSeconds(1));
        var wiring = new PlantWiring(baud);
        NodeClock clock = NodeClock.system();
        SerialLink link;
        if (port.equals(SIMULATED)) {
            link = resources.closeAfterNode(new SimulatedPlant(wiring, theta2, report, clock, System.out)).hostEnd();
        } else {
            for (String simulatedOnly : new String[] {"theta2", "report"}) {
                if (settings.has(simulatedOnly)) {
                    throw settings.invalid(simulatedOnly, "only the simulated board has it; remove it, or write"
                            + " port=\"" + SIMULATED + "\"");
                }
            }
            try {
                link = resources.closeAfterNode(JSerialCommLink.open(port, baud));
            } catch (IOException | RuntimeException e) {
                throw settings.invalid("port", "cannot open " + port + " (" + e.getMessage() + "); name a serial"
                        + " port that exists and that this user may open, or write " + SIMULATED);
            }
        }
        return DspProxy.factory(new DspClient(link, clock, wiring.client()));
    }
}
