package io.etherware.examples.migrate;

import io.etherware.examples.scenario.ConfiguredController;
import io.etherware.pendulum.control.GainSet;
import io.etherware.pendulum.plant.PendulumParameters;

/**
 * The migration scenario's controller: the pendulum controller with the soft gain set
 * {@link GainSet#v1Soft}, constructed from a configuration string as a migration's target node
 * constructs it. {@code listener=<name>} is required: each node reports the cycles its instance
 * runs to the listener of that name in its own JVM.
 */
public final class ListenedController extends ConfiguredController {

    /** The controller telling the listener named in {@code configuration} ({@code listener=<name>}) about each cycle. */
    public ListenedController(String configuration) {
        super(GainSet.v1Soft(PendulumParameters.defaults()), requireListener(configuration));
    }

    private static String requireListener(String configuration) {
        if (listenerName(configuration) == null) {
            throw new IllegalArgumentException("configuration='" + configuration
                    + "' names no listener: give listener=<name>");
        }
        return configuration;
    }
}
