package io.etherware.services.management;

import static org.junit.jupiter.api.Assertions.assertEquals;
import static org.junit.jupiter.api.Assertions.assertInstanceOf;
import static org.junit.jupiter.api.Assertions.assertThrows;
import static org.junit.jupiter.api.Assertions.assertTrue;

import example.counter.ReportingCounter;
import io.etherware.core.kernel.Endpoint;
import io.etherware.core.message.Profile;
import io.etherware.testkit.Await;
import java.time.Duration;
import java.util.concurrent.CompletableFuture;
import java.util.concurrent.ExecutionException;
import java.util.concurrent.TimeUnit;
import org.junit.jupiter.api.Test;

/**
 * Management requests that meet on a node: queued in arrival order up to a bound, refused beyond
 * it with a clear answer; two nodes migrating components to each other at the same time.
 */
class ManagementConcurrencyIT {

    private static final Profile LEFT = Profile.parse("counter[test=left]");
    private static final Profile RIGHT = Profile.parse("counter[test=right]");

    @Test
    void shouldMigrateComponentsBetweenTwoNodesInBothDirectionsAtOnce() throws Exception {
        // Each node's migration away waits for the other's answers; the steps into a node are
        // served apart from its own migration, so neither waits for the other's step timeout.
        ManagementConfig config = MigrationNode.config().migrationStepTimeout(Duration.ofSeconds(10))
                .handoverWait(Duration.ofSeconds(20)).build();
        try (var a = MigrationNode.start("cross-a", config);
             var b = MigrationNode.start("cross-b", config, a.address())) {
            a.node.add(LEFT, ReportingCounter::new);
            b.node.add(RIGHT, ReportingCounter::new);
            a.awaitManagementOf("cross-b");
            b.awaitManagementOf("cross-a");
            for (int round = 0; round < 5; round++) {
                String leftFrom = round % 2 == 0 ? "cross-a" : "cross-b";
                String rightFrom = round % 2 == 0 ? "cross-b" : "cross-a";
                CompletableFuture<MigrationResult> left = Management.migrate(a.node, leftFrom, LEFT, rightFrom);
                CompletableFuture<MigrationResult> right = Management.migrate(b.node, rightFrom, RIGHT, leftFrom);
                MigrationResult leftMoved = left.get(60, TimeUnit.SECONDS);
                MigrationResult rightMoved = right.get(60, TimeUnit.SECONDS);
                assertEquals(rightFrom, leftMoved.toNode());
                assertEquals(leftFrom, rightMoved.toNode());
            }
            assertEquals(10, a.management.migratedCount() + b.management.migratedCount(), "five each way");
            // Before the steps had a thread of their own, each waited for the other's step timeout and failed.
            assertEquals(0, a.management.failedCount() + b.management.failedCount());
        }
    }

    @Test
    void shouldRefuseARequestBeyondTheQueueWithBusyAndServeTheOneInProgress() throws Exception {
        ManagementConfig noQueue = MigrationNode.config().maxQueuedOperations(0).build();
        try (var a = MigrationNode.start("busy-a", noQueue);
             var b = MigrationNode.start("busy-b", MigrationNode.config().build(), a.address())) {
            a.node.add(LEFT, ReportingCounter::new);
            a.node.add(RIGHT, ReportingCounter::new);
            a.awaitManagementOf("busy-b");
            // Both requests reach A's service in this order, on its dispatcher: the first occupies
            // the worker (its target restores slowly), the second finds no room.
            CompletableFuture<MigrationResult> first = Management.migrate(a.node, "busy-a",
                    new MigrateRequest(LEFT, "busy-b", ReportingCounter.SlowRestore.class.getName(), null, null),
                    Duration.ofSeconds(30));
            CompletableFuture<MigrationResult> second = Management.migrate(a.node, "busy-a", RIGHT, "busy-b");

            var error = assertThrows(ExecutionException.class, () -> second.get(30, TimeUnit.SECONDS));
            ManagementFailure busy = assertInstanceOf(ManagementException.class, error.getCause()).failure();
            assertEquals(ManagementFailure.Reason.BUSY, busy.reason(), busy.error());
            assertTrue(busy.error().contains("node 'busy-a'") && busy.error().contains("ask again later"),
                    busy.error());
            assertEquals(1, a.management.busyCount());
            assertInstanceOf(Endpoint.Local.class, a.node.registry().resolve(RIGHT), "the refused one stays");

            assertEquals("busy-b", first.get(30, TimeUnit.SECONDS).toNode(), "the one in progress went on");
            Await.until("A routes the moved one to B", () -> a.node.registry().resolve(LEFT) instanceof Endpoint.Remote);
            // Room again: the same request is served now.
            assertEquals("busy-b", Management.migrate(a.node, "busy-a", RIGHT, "busy-b").get(30, TimeUnit.SECONDS)
                    .toNode());
        }
    }
}
