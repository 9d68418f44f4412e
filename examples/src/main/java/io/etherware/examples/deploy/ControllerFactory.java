package io.etherware.examples.deploy;

import io.etherware.core.component.Component;
import io.etherware.core.message.ContentsTypes;
import io.etherware.deploy.ComponentFactory;
import io.etherware.deploy.DeploymentException;
import io.etherware.deploy.Settings;
import io.etherware.deploy.view.LiveSignals;
import io.etherware.examples.scenario.PendulumRig;
import io.etherware.pendulum.components.ControlCycle;
import io.etherware.pendulum.components.ControlListener;
import io.etherware.pendulum.components.ControllerConfig;
import io.etherware.pendulum.components.DspProxy;
import io.etherware.pendulum.components.PendulumContents;
import io.etherware.pendulum.components.PendulumController;
import io.etherware.pendulum.control.GainSet;
import java.util.function.Supplier;

/**
 * The pendulum's {@link PendulumController} in a deployment file. Settings, all optional:
 * <ul>
 *   <li>{@code gains}: {@code v1-soft} (default) or {@code v2-tight}, the paper's two gain sets;</li>
 *   <li>{@code dspProxy}: the DSPProxy's profile or a query for it (default
 *       {@code dsp-proxy[pendulum=1]}), on this node or a peer;</li>
 *   <li>{@code replyTimeout}: how long a cycle waits for its reading (default 10ms, below the
 *       paper's 15 ms period).</li>
 * </ul>
 * The controller runs one cycle per Tick it receives: subscribe it to a Notifier. Each cycle is
 * published to the node's live signals ({@link ComponentFactory.Resources#signals}), which a
 * {@code <view>} plots: {@value #THETA1} and {@value #THETA2} (the measured angles, rad),
 * {@value #TORQUE} (the torque commanded, N·m; none when the cycle missed its reading) and
 * {@value #LATENESS} (how late the cycle started after its Tick's release, ms).
 */
public final class ControllerFactory implements ComponentFactory {

    /** The live signal of the measured arm angle θ1, rad. */
    public static final String THETA1 = "theta1";
    /** The live signal of the measured pendulum angle θ2 off upright, rad. */
    public static final String THETA2 = "theta2";
    /** The live signal of the torque commanded, N·m. */
    public static final String TORQUE = "u";
    /** The live signal of the cycle's start after its Tick's release, ms. */
    public static final String LATENESS = "tickLateness";

    /** Made by the launcher. */
    public ControllerFactory() {
    }

    @Override
    public void registerContents(ContentsTypes types) {
        PendulumContents.register(types);
    }

    @Override
    public Supplier<? extends Component> create(Settings settings, Resources resources) throws DeploymentException {
        ControllerConfig defaults = ControllerConfig.defaults();
        GainSet gains = switch (settings.string("gains", "v1-soft")) {
            case "v1-soft" -> GainSet.v1Soft(PendulumRig.PARAMETERS);
            case "v2-tight" -> GainSet.v2Tight(PendulumRig.PARAMETERS);
            default -> throw settings.invalid("gains", "write v1-soft or v2-tight (the paper's gain sets)");
        };
        ControllerConfig config = defaults.withDspProxy(settings.profile("dspProxy", DspProxy.DEFAULT_PROFILE));
        try {
            config = config.withReplyTimeout(settings.duration("replyTimeout",
                    java.time.Duration.ofNanos(defaults.replyTimeoutNs())));
        } catch (IllegalArgumentException e) {
            throw settings.invalid("replyTimeout", e.getMessage());
        }
        return PendulumController.factory(config, gains, publisher(resources.signals()));
    }

    /**
     * Records each cycle into four live signals. Runs on the controller's dispatcher: four
     * allocation-free stores, no lock.
     */
    private static ControlListener publisher(LiveSignals signals) {
        LiveSignals.Signal theta1 = signals.create(THETA1, "rad");
        LiveSignals.Signal theta2 = signals.create(THETA2, "rad");
        LiveSignals.Signal torque = signals.create(TORQUE, "N·m");
        LiveSignals.Signal lateness = signals.create(LATENESS, "ms");
        return (ControlCycle cycle) -> {
            long atNs = cycle.startNs();
            theta1.record(atNs, cycle.theta1Rad());
            theta2.record(atNs, cycle.theta2Rad());
            torque.record(atNs, cycle.torqueNm());
            lateness.record(atNs, cycle.startLatenessNs() / 1e6);
        };
    }
}
