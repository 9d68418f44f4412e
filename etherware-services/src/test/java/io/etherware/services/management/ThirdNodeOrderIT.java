package io.etherware.services.management;

import static org.junit.jupiter.api.Assertions.assertEquals;
import static org.junit.jupiter.api.Assertions.assertTrue;

import example.counter.ReportingCounter;
import io.etherware.core.message.Profile;
import io.etherware.testkit.Await;
import java.util.List;
import java.util.concurrent.TimeUnit;
import org.junit.jupiter.api.Test;

/**
 * Order per sender across migrations for a sender on neither node (issue 16, item 2): node C
 * streams to a component that moves between A and B, so C's route to it switches from one node
 * to the other under the stream while C's earlier messages are still on their way through the
 * old node.
 */
class ThirdNodeOrderIT {

    private static final Profile COUNTER = Profile.parse("counter[test=third-node]");
    private static final long STREAM_PERIOD_NS = TimeUnit.MILLISECONDS.toNanos(1);
    private static final int ROUND_TRIPS = 10;

    @Test
    void shouldKeepAThirdNodesStreamInOrderThroughRepeatedMoves() throws Exception {
        try (var a = MigrationNode.start("ord-a", MigrationNode.config().build());
             var b = MigrationNode.start("ord-b", MigrationNode.config().build(), a.address());
             var c = MigrationNode.start("ord-c", MigrationNode.config().build(), a.address(), b.address())) {
            a.node.add(COUNTER, ReportingCounter::new);
            a.awaitManagementOf("ord-b");
            b.awaitManagementOf("ord-a");
            Await.until("B and C route the counter", () -> b.node.registry().profiles().contains(COUNTER)
                    && c.node.registry().profiles().contains(COUNTER));
            // The sink's announcement reaches A and B ahead of C's first message on each lane.
            var stream = new SeqStream(c.node, COUNTER, STREAM_PERIOD_NS);
            Await.until("A and B route the sink", () -> List.of(a, b).stream()
                    .allMatch(node -> node.node.registry().profiles().contains(ReportingCounter.SINK)));
            stream.awaitMore(100);

            for (int i = 0; i < ROUND_TRIPS; i++) {
                Management.migrate(a.node, "ord-a", COUNTER, "ord-b").get(30, TimeUnit.SECONDS);
                stream.awaitMore(40);
                Management.migrate(a.node, "ord-b", COUNTER, "ord-a").get(30, TimeUnit.SECONDS);
                stream.awaitMore(40);
            }
            stream.stopAndAssertExactlyOnceInOrder();
            assertEquals(2 * ROUND_TRIPS + 1, stream.handlers().size(), "A, then B and A in turn: " + stream.handlers());
            for (MigrationNode node : List.of(a, b, c)) {
                assertEquals(0, node.node.stats().undeliverable(), node.node.nodeId() + " lost nothing");
            }
            // The order came from the protocol, not from luck: C's route moved with every migration
            // (its stream never stopped), and each move's marker was answered.
            var stats = c.net.stats();
            assertTrue(stats.routeMoves() >= 2L * ROUND_TRIPS, "C's route moved with each migration: " + stats);
            assertEquals(0, stats.routeMovesUnconfirmed(), "every marker was answered: " + stats);
        }
    }
}
