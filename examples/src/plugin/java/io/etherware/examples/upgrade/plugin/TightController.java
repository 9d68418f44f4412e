package io.etherware.examples.upgrade.plugin;

import io.etherware.examples.scenario.ConfiguredController;
import io.etherware.examples.scenario.ControlListeners;
import io.etherware.pendulum.components.ControlListener;
import io.etherware.pendulum.control.GainSet;
import io.etherware.pendulum.plant.PendulumParameters;

/**
 * Controller V2 of the upgrade scenario (paper Section VI-C1): the pendulum controller with the
 * tight gain set {@link GainSet#v2Tight}. The build compiles it apart from the examples and packs
 * it alone into a plugin jar ({@code examples/target/plugins/*-controller-v2.jar}), which the
 * management service loads at runtime into a class loader of its own; it is not on the node's
 * class path.
 *
 * <p>The management service constructs it with a configuration string:
 * {@code listener=<name>} names the scenario's {@link ControlListener} in
 * {@link ControlListeners}. It takes over V1's state (estimator memory, θ1r, counters) in
 * {@link #restore}, so the loop continues where V1 left it. Called by the kernel one message at a
 * time, like any component.
 */
public final class TightController extends ConfiguredController {

    /** V2 without a listener. */
    public TightController() {
        this("");
    }

    /** V2 telling the listener named in {@code configuration} ({@code listener=<name>}) about each cycle. */
    public TightController(String configuration) {
        super(GainSet.v2Tight(PendulumParameters.defaults()), configuration);
    }
}
