package io.etherware.core.kernel;

import static org.junit.jupiter.api.Assertions.assertEquals;
import static org.junit.jupiter.api.Assertions.assertInstanceOf;
import static org.junit.jupiter.api.Assertions.assertThrows;
import static org.junit.jupiter.api.Assertions.assertTrue;

import io.etherware.core.component.RequestFailedException;
import io.etherware.core.component.Shell;
import io.etherware.core.message.Profile;
import io.etherware.core.message.QoS;
import io.etherware.core.message.Text;
import io.etherware.core.testing.Await;
import io.etherware.core.testing.MultiDispatcherScheduler;
import io.etherware.core.testing.Num;
import java.time.Duration;
import java.util.concurrent.CompletableFuture;
import java.util.concurrent.ExecutionException;
import java.util.concurrent.TimeUnit;
import org.junit.jupiter.api.Test;

/** Close never loses a message without counting it. */
class CloseTest {

    private static final Profile SLOW = Profile.of("slow");
    private static final int QUEUED = 1_000;

    private static void closeWithQueuedMessages(EtherwareNode node) throws Exception {
        Shell slow = node.add(SLOW, () -> (message, context) -> Thread.sleep(2));
        node.start();
        for (int i = 0; i < QUEUED; i++) {
            node.send(SLOW, new Num(i));
        }
        node.close();

        NodeStats stats = node.stats();
        assertEquals(QUEUED, slow.handledCount() + stats.discarded(),
                "every queued message is delivered or counted as discarded: " + stats);
        assertTrue(stats.discarded() > 0, "2 s of work cannot finish in a 100 ms drain: " + stats);
        assertTrue(slow.handledCount() > 0);
        assertEquals(Shell.State.STOPPED, slow.state());
    }

    @Test
    void shouldAccountForEveryQueuedMessageWhenClosingTheFifoScheduler() throws Exception {
        closeWithQueuedMessages(EtherwareNode.builder().nodeId("close-fifo").drainTimeout(Duration.ofMillis(100)).build());
    }

    @Test
    void shouldAccountForEveryQueuedMessageWhenClosingWithJobsParkedAtTheComponent() throws Exception {
        // Round robin over 3 dispatchers: most jobs wait parked at the busy component.
        closeWithQueuedMessages(EtherwareNode.builder().nodeId("close-multi")
                .scheduler(() -> MultiDispatcherScheduler.roundRobin(3)).drainTimeout(Duration.ofMillis(100)).build());
    }

    @Test
    void shouldCountMessagesSentAfterCloseAsDiscarded() {
        var node = EtherwareNode.builder().nodeId("close-after").build();
        node.add(SLOW, () -> (message, context) -> { });
        node.start();
        node.close();
        node.send(SLOW, new Text("too late"));
        assertEquals(1, node.stats().discarded());
        assertThrows(IllegalStateException.class, () -> node.add(Profile.of("late"), () -> (m, c) -> { }));
    }

    @Test
    void shouldFailWaitingRequestsWhenTheNodeCloses() throws Exception {
        var node = EtherwareNode.builder().nodeId("close-requests").drainTimeout(Duration.ZERO).build();
        node.add(SLOW, () -> (message, context) -> { }); // never replies
        node.start();
        CompletableFuture<?> reply = node.request(SLOW, new Text("?"), QoS.NONE,
                TimeUnit.MINUTES.toNanos(5));
        Await.until("the request is handled", () -> node.shell(SLOW).handledCount() == 1);
        node.close();
        var error = assertThrows(ExecutionException.class, () -> reply.get(30, TimeUnit.SECONDS));
        var failure = assertInstanceOf(RequestFailedException.class, error.getCause());
        assertEquals(RequestFailedException.Reason.NODE_CLOSED, failure.reason());
    }

    @Test
    void shouldRefuseCloseOnADispatcherThreadAndOfferCloseAsync() throws Exception {
        var outcome = new CompletableFuture<String>();
        try (var node = EtherwareNode.builder().nodeId("close-self").build()) {
            node.add(SLOW, () -> (message, context) -> {
                try {
                    EtherwareNodeHolder.node.close();
                    outcome.complete("closed");
                } catch (IllegalStateException e) {
                    outcome.complete(e.getMessage());
                }
            });
            EtherwareNodeHolder.node = node;
            node.start();
            node.send(SLOW, new Text("close yourself"));
            assertTrue(outcome.get(30, TimeUnit.SECONDS).contains("Use closeAsync()"));
            assertTrue(node.isRunning());
        }
    }

    /** Hands the node to its own component in the test above. */
    private static final class EtherwareNodeHolder {
        static volatile EtherwareNode node;
    }
}
