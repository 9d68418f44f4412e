package io.etherware.examples.migrate;

import io.etherware.core.codec.MessageCodec;
import io.etherware.core.kernel.Kernel;
import io.etherware.core.message.Contents;
import io.etherware.core.message.Criticality;
import io.etherware.core.message.Message;
import io.etherware.core.message.MessageId;
import io.etherware.core.message.Profile;
import io.etherware.core.message.QoS;
import io.etherware.core.message.Tick;
import io.etherware.pendulum.components.AnglesReading;
import io.etherware.pendulum.components.ControlCycle;
import io.etherware.pendulum.components.ControlListener;
import io.etherware.pendulum.components.ControllerConfig;
import io.etherware.pendulum.components.DspProxy;
import io.etherware.pendulum.components.PendulumContents;
import io.etherware.pendulum.components.PendulumController;
import io.etherware.pendulum.components.ReadAngles;
import io.etherware.pendulum.components.SetTorque;
import io.etherware.pendulum.control.GainSet;
import io.etherware.pendulum.plant.PendulumParameters;
import java.util.List;

/**
 * Warms a JVM of the migration scenario up before the pendulum starts, so that the first control
 * cycles across the network do not pay for class loading, Jackson's first use of each contents
 * type and interpreted code: a fresh JVM's first cycles were late by tens to hundreds of
 * milliseconds, and the pendulum doubles its angle in about 90 ms. Each node's messenger gets a
 * codec of its own, warmed here with every contents type the loop and the migration send.
 *
 * <p>Stateless; call from one thread before the node starts its messenger.
 */
public final class WarmUp {

    /** Encode and decode rounds per message type: enough for the JIT's first tiers. */
    private static final int ROUNDS = 3_000;
    /** A profile only the warm-up uses: the spare controller that the scenario migrates once first. */
    public static final Profile REHEARSAL = Profile.of("controller", "pendulum", "rehearsal");

    private WarmUp() {
    }

    /**
     * A codec for a node's messenger over the node's contents types, with the scenario's message
     * types registered there, warmed with them.
     */
    public static MessageCodec warmedCodec(Kernel node) {
        String nodeId = node.nodeId();
        PendulumContents.register(node.contentsTypes());
        CycleReport.register(node.contentsTypes());
        MessageCodec codec = MessageCodec.builder().contentsTypes(node.contentsTypes()).build();
        long periodNs = 15_000_000L;
        List<Contents> samples = List.of(
                new Tick(1_000_000L, 1, periodNs),
                new ReadAngles(1),
                new AnglesReading(1, 1, 2048, 4, 1_000, 0.01, -0.02),
                new SetTorque(1, 0.05),
                new CycleReport(new ControlCycle(1, 1_000_000L, 1_010_000L, 1_020_000L, ControlCycle.Outcome.COMMANDED,
                        0.01, -0.02, 0.1, -0.2, 1_000, 0.05, 1)),
                new PendulumController(ControllerConfig.defaults(), GainSet.v1Soft(PendulumParameters.defaults()),
                        ControlListener.NONE).snapshot());
        QoS high = QoS.periodic(Criticality.HIGH, periodNs);
        long sink = 0;
        for (int round = 0; round < ROUNDS; round++) {
            for (Contents contents : samples) {
                var message = new Message(DspProxy.DEFAULT_PROFILE, PendulumController.DEFAULT_PROFILE, round, high,
                        contents, new MessageId(nodeId, round + 1), null);
                sink += codec.decode(codec.encode(message)).timeStamp();
            }
        }
        if (sink == Long.MIN_VALUE) {
            throw new AssertionError("unreachable: keeps the loop from being optimized away");
        }
        return codec;
    }
}
