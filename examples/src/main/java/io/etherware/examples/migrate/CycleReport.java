package io.etherware.examples.migrate;

import io.etherware.core.component.Component;
import io.etherware.core.kernel.EtherwareNode;
import io.etherware.core.message.Contents;
import io.etherware.core.message.ContentsTypes;
import io.etherware.core.message.Criticality;
import io.etherware.core.message.Profile;
import io.etherware.core.message.QoS;
import io.etherware.pendulum.components.ControlCycle;
import io.etherware.pendulum.components.ControlListener;
import java.util.Objects;
import java.util.function.Supplier;

/**
 * One control cycle of a controller in another JVM, on its way to the scenario's recorder on the
 * plant's node, registered as {@code scenario.controlCycle}. The cycle's times are the
 * controller's monotonic clock: the scenario runs both JVMs on one host, whose
 * {@code CLOCK_MONOTONIC} they share, so the recorder uses them as they are. Immutable.
 *
 * @param cycle the cycle as the controller saw it
 */
public record CycleReport(ControlCycle cycle) implements Contents {

    /** The wire name. */
    public static final String TYPE = "scenario.controlCycle";
    /** The profile of the recorder on the plant's node. */
    public static final Profile RECORDER = Profile.of("scenario.cycleRecorder");
    /** Below the controller's HIGH Ticks and the DSPProxy's traffic: the report must never delay control. */
    public static final QoS QOS = QoS.of(Criticality.LOW);

    public CycleReport {
        Objects.requireNonNull(cycle, "cycle");
    }

    /**
     * Registers the type in {@code types} (idempotent); every node of the scenario does, on its own
     * registry.
     */
    public static ContentsTypes register(ContentsTypes types) {
        return types.register(TYPE, CycleReport.class);
    }

    /**
     * A listener that sends each cycle to the {@link #RECORDER} through {@code node}; it is
     * called on the controller's dispatcher and only hands a message to the kernel, which does not
     * block.
     */
    public static ControlListener forwarder(EtherwareNode node) {
        Objects.requireNonNull(node, "node");
        register(node.contentsTypes());
        return cycle -> node.send(RECORDER, new CycleReport(cycle), QOS);
    }

    /**
     * The recorder on {@code node}: a component that hands every report it receives to
     * {@code listener}. Registers the type in the node's registry.
     */
    public static Supplier<Component> recorder(EtherwareNode node, ControlListener listener) {
        Objects.requireNonNull(listener, "listener");
        register(node.contentsTypes());
        return () -> (message, context) -> listener.onCycle(message.contentsAs(CycleReport.class).cycle());
    }
}
