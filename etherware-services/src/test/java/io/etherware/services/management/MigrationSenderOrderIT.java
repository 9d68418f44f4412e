package io.etherware.services.management;

import static org.junit.jupiter.api.Assertions.assertEquals;
import static org.junit.jupiter.api.Assertions.assertTrue;

import example.counter.ReportingCounter;
import io.etherware.core.kernel.Endpoint;
import io.etherware.core.message.Profile;
import io.etherware.testkit.Await;
import java.util.List;
import java.util.concurrent.TimeUnit;
import org.junit.jupiter.api.Test;

/**
 * Order per sender across a move, for a sender on a third node: node C streams to a counter that
 * moves between A and B. C learns of each move only when the source withdraws the profile, so it
 * sends its last messages to the source and its next ones to the target straight away; those
 * must not overtake the ones the source forwards.
 */
class MigrationSenderOrderIT {

    private static final Profile COUNTER = Profile.parse("counter[test=sender-order]");
    /** Bursts of back-to-back messages, so consecutive ones leave closer together than a network hop. */
    private static final int BURST = 4;
    private static final long PERIOD_NS = TimeUnit.MILLISECONDS.toNanos(2);
    private static final int ROUND_TRIPS = 15;

    @Test
    void shouldHandleAThirdNodesStreamInOrderExactlyOnceThroughManyMoves() throws Exception {
        try (var a = MigrationNode.start("ord-a", MigrationNode.config().build());
             var b = MigrationNode.start("ord-b", MigrationNode.config().build(), a.address());
             var c = MigrationNode.start("ord-c", MigrationNode.config().build(), a.address(), b.address())) {
            a.node.add(COUNTER, ReportingCounter::new);
            a.awaitManagementOf("ord-b");
            b.awaitManagementOf("ord-a");
            Await.until("C routes the counter to A", () -> c.node.registry().profiles().contains(COUNTER)
                    && c.node.registry().resolve(COUNTER) instanceof Endpoint.Remote remote
                    && remote.route().isServedBy("ord-a"));
            var stream = new SeqStream(c.node, COUNTER, PERIOD_NS, BURST);
            Await.until("A, B and C route the sink", () -> List.of(a, b).stream().allMatch(node ->
                    node.node.registry().profiles().contains(ReportingCounter.SINK)));
            stream.awaitMore(200);

            for (int i = 0; i < ROUND_TRIPS; i++) {
                Management.migrate(a.node, "ord-a", COUNTER, "ord-b").get(30, TimeUnit.SECONDS);
                stream.awaitMore(80);
                Management.migrate(a.node, "ord-b", COUNTER, "ord-a").get(30, TimeUnit.SECONDS);
                stream.awaitMore(80);
            }
            stream.stopAndAssertExactlyOnceInOrder();
            assertEquals(2 * ROUND_TRIPS + 1, stream.handlers().size(), "A, then B and A in turn: " + stream.handlers());
            assertEquals(0, a.node.stats().undeliverable() + b.node.stats().undeliverable()
                    + c.node.stats().undeliverable(), "nothing undeliverable");
            var network = c.net.stats();
            assertTrue(network.routeFlushes() >= ROUND_TRIPS, "C held its lane behind a marker at most moves: " + network);
            assertEquals(0, network.routeFlushTimeouts(), "every flush was answered: " + network);
        }
    }
}
