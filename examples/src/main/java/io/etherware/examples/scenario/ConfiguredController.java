package io.etherware.examples.scenario;

import io.etherware.core.component.Component;
import io.etherware.core.component.ComponentContext;
import io.etherware.core.component.ComponentState;
import io.etherware.core.message.Message;
import io.etherware.pendulum.components.ControlListener;
import io.etherware.pendulum.components.ControllerConfig;
import io.etherware.pendulum.components.PendulumController;
import io.etherware.pendulum.control.GainSet;

/**
 * A {@link PendulumController} with a fixed gain set, for a node to construct from a class name and
 * a configuration string, as the management service does for an upgrade or a migration:
 * {@code listener=<name>} names the {@link ControlListener} registered in {@link ControlListeners}
 * of the JVM it runs in. It carries the controller's state both ways (estimator memory, θ1r,
 * counters), so an instance continues where the one before it stopped. Called by the kernel one
 * message at a time, like any component.
 */
public abstract class ConfiguredController implements Component {

    private final PendulumController controller;

    /** The controller computing with {@code gains}, telling the listener {@code configuration} names (or none). */
    protected ConfiguredController(GainSet gains, String configuration) {
        controller = new PendulumController(ControllerConfig.defaults(), gains,
                ControlListeners.named(listenerName(configuration)));
    }

    /** The configuration that names {@code listener}. */
    public static String configuration(String listener) {
        return "listener=" + listener;
    }

    /** The listener name in {@code configuration} ({@code listener=<name>}), or null if it names none. */
    public static String listenerName(String configuration) {
        for (String entry : configuration.split(",")) {
            String[] pair = entry.trim().split("=", 2);
            if (pair.length == 2 && pair[0].trim().equals("listener")) {
                return pair[1].trim();
            }
        }
        return null;
    }

    @Override
    public final void onStart(ComponentContext context) {
        controller.onStart(context);
    }

    @Override
    public final void onMessage(Message message, ComponentContext context) {
        controller.onMessage(message, context);
    }

    @Override
    public final void onStop() {
        controller.onStop();
    }

    @Override
    public final ComponentState snapshot() {
        return controller.snapshot();
    }

    @Override
    public final void restore(ComponentState state) {
        controller.restore(state);
    }
}
