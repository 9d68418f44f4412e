package io.etherware.examples.migrate;

import io.etherware.core.component.Component;
import io.etherware.core.component.ComponentContext;
import io.etherware.core.component.ComponentState;
import io.etherware.core.message.Message;
import io.etherware.examples.scenario.ControlListeners;
import io.etherware.pendulum.components.ControllerConfig;
import io.etherware.pendulum.components.PendulumController;
import io.etherware.pendulum.control.GainSet;
import io.etherware.pendulum.plant.PendulumParameters;

/**
 * The migration scenario's controller: the {@link PendulumController} with the soft gain set
 * {@link GainSet#v1Soft}, constructed from a configuration string as a migration's target node
 * constructs it: {@code listener=<name>} names the {@link io.etherware.pendulum.components.ControlListener}
 * registered in {@link ControlListeners} of the JVM it runs in, so each node reports the cycles its
 * instance runs. Its state is the controller's, so the instance at the target continues where the
 * one at the source stopped. Called by the kernel one message at a time, like any component.
 */
public final class ListenedController implements Component {

    private final PendulumController controller;

    /** The controller telling the listener named in {@code configuration} ({@code listener=<name>}) about each cycle. */
    public ListenedController(String configuration) {
        controller = new PendulumController(ControllerConfig.defaults(), GainSet.v1Soft(PendulumParameters.defaults()),
                ControlListeners.named(listenerName(configuration)));
    }

    /** The configuration that names {@code listener}. */
    public static String configuration(String listener) {
        return "listener=" + listener;
    }

    private static String listenerName(String configuration) {
        for (String entry : configuration.split(",")) {
            String[] pair = entry.trim().split("=", 2);
            if (pair.length == 2 && pair[0].trim().equals("listener")) {
                return pair[1].trim();
            }
        }
        throw new IllegalArgumentException("configuration='" + configuration + "' names no listener: give listener=<name>");
    }

    @Override
    public void onStart(ComponentContext context) {
        controller.onStart(context);
    }

    @Override
    public void onMessage(Message message, ComponentContext context) {
        controller.onMessage(message, context);
    }

    @Override
    public void onStop() {
        controller.onStop();
    }

    @Override
    public ComponentState snapshot() {
        return controller.snapshot();
    }

    @Override
    public void restore(ComponentState state) {
        controller.restore(state);
    }
}
