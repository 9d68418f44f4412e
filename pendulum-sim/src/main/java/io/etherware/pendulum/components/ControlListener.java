package io.etherware.pendulum.components;

/**
 * Observes a {@link PendulumController}'s cycles, for plots and tests.
 *
 * <p>Called on the controller's dispatcher thread, inside its turn, once per completed or missed
 * cycle: it must be quick and must not block (append to a buffer, e.g. {@link ControlRecorder}).
 * An exception it throws is logged and otherwise ignored.
 */
@FunctionalInterface
public interface ControlListener {

    /** A listener that does nothing. */
    ControlListener NONE = cycle -> { };

    /**
     * One cycle ended, commanded or missed. Called on the controller's dispatcher thread; must not
     * block.
     *
     * @param cycle what the controller measured and commanded in the cycle
     */
    void onCycle(ControlCycle cycle);
}
