package io.etherware.core.kernel;

import io.etherware.core.message.Criticality;
import io.etherware.core.message.Profile;
import io.etherware.core.message.QoS;
import io.etherware.core.message.Text;
import java.util.Objects;
import java.util.concurrent.ExecutionException;
import java.util.concurrent.TimeUnit;
import java.util.concurrent.TimeoutException;

/**
 * Runs a node's delivery path before its real-time part depends on it: requests and their replies
 * through the kernel, at every criticality, one at a time, to a throwaway echo component removed
 * afterwards. The first use of a path loads its classes, and inside the JVM that can mean waiting
 * for an ordinary thread; two real-time threads doing so at once on a machine with as many cores
 * hold every CPU until the kernel's real-time throttling (docs/REALTIME.md, "First use at
 * real-time priority"). Here the first use happens on one dispatcher at a time, before the plant
 * or the network depend on any of them.
 *
 * <p>Stateless; call from an ordinary thread (it blocks), once the node has started.
 */
public final class DeliveryWarmUp {

    /** Request rounds per criticality: the first loads the classes, the rest start the JIT on them. */
    public static final int ROUNDS = 200;
    private static final long TIMEOUT_NS = TimeUnit.SECONDS.toNanos(10);

    private DeliveryWarmUp() {
    }

    /**
     * Warms {@code node}'s delivery path up (see the class documentation).
     *
     * @param node a started node
     * @throws IllegalStateException if the node does not run, or a round trip fails or takes over 10 s
     */
    public static void run(EtherwareNode node) {
        Objects.requireNonNull(node, "node");
        Profile echo = Profile.of("etherware.warm-up", "node", node.nodeId());
        node.add(echo, () -> (message, context) -> context.reply(message, message.contents()));
        try {
            for (int round = 0; round < ROUNDS; round++) {
                for (Criticality criticality : Criticality.values()) {
                    node.request(echo, new Text("warm-up"), QoS.of(criticality), TIMEOUT_NS)
                            .get(TIMEOUT_NS, TimeUnit.NANOSECONDS);
                }
            }
        } catch (ExecutionException | TimeoutException e) {
            throw new IllegalStateException("the warm-up round trip through node '" + node.nodeId() + "' failed: " + e,
                    e);
        } catch (InterruptedException e) {
            Thread.currentThread().interrupt();
            throw new IllegalStateException("interrupted warming up node '" + node.nodeId() + "'", e);
        } finally {
            node.remove(echo);
        }
    }
}
