package io.etherware.core.kernel;

import static org.junit.jupiter.api.Assertions.assertEquals;
import static org.junit.jupiter.api.Assertions.assertFalse;
import static org.junit.jupiter.api.Assertions.assertThrows;
import static org.junit.jupiter.api.Assertions.assertTrue;

import io.etherware.core.message.Criticality;
import io.etherware.core.message.Message;
import io.etherware.core.message.Profile;
import io.etherware.core.message.QoS;
import io.etherware.core.testing.Await;
import io.etherware.core.testing.MultiDispatcherScheduler;
import io.etherware.core.testing.Num;
import java.time.Duration;
import java.util.List;
import java.util.concurrent.CompletableFuture;
import java.util.concurrent.CopyOnWriteArrayList;
import java.util.concurrent.CountDownLatch;
import java.util.concurrent.TimeUnit;
import org.junit.jupiter.api.Test;

/**
 * A hold that waits for the component to be quiescent ({@link ComponentHost#holdAsync(Profile, Duration)}):
 * the outcomes of its requests in flight reach it before it is held, so a migration that holds it
 * so leaves no reply behind; a reply that never comes holds it anyway at the end of the wait. A
 * swap waits the same way ({@link ComponentHost#swapAsync(Profile, java.util.function.Supplier,
 * java.util.function.LongConsumer, Duration)}). A hold also waits for the messages of other
 * components already queued for the component (a swap does not), but not for those it sends itself.
 */
class QuiescentHoldTest {

    private static final Profile REQUESTER = Profile.of("requester");
    private static final Profile RESPONDER = Profile.of("responder");
    private static final long REQUEST_TIMEOUT_NS = TimeUnit.SECONDS.toNanos(60);

    /** Asks the responder on each Num; records what each request came to. */
    private static void addRequester(EtherwareNode node, List<String> outcomes, List<Long> handled) {
        node.add(REQUESTER, () -> (message, context) -> {
            if (message.contents() instanceof Num num) {
                handled.add(num.value());
                context.request(RESPONDER, num, QoS.of(Criticality.HIGH), REQUEST_TIMEOUT_NS)
                        .whenComplete((reply, failure) -> outcomes.add(failure == null ? "reply " + num.value()
                                : "failed " + num.value()));
            }
        });
    }

    /** Answers each request once {@code gate} is open. */
    private static void addResponder(EtherwareNode node, CountDownLatch gate, List<Long> asked) {
        node.add(RESPONDER, () -> (message, context) -> {
            asked.add(message.contentsAs(Num.class).value());
            if (gate.await(30, TimeUnit.SECONDS)) {
                context.reply(message, message.contents());
            }
        });
    }

    private final List<String> outcomes = new CopyOnWriteArrayList<>();
    private final List<Long> handled = new CopyOnWriteArrayList<>();
    private final List<Long> asked = new CopyOnWriteArrayList<>();
    private final CountDownLatch answer = new CountDownLatch(1);

    /** A started node whose requester has asked the responder once, the reply held back by {@link #answer}. */
    private EtherwareNode requestInFlight(String nodeId) throws InterruptedException {
        var node = EtherwareNode.builder().nodeId(nodeId).scheduler(() -> MultiDispatcherScheduler.roundRobin(2))
                .build();
        addRequester(node, outcomes, handled);
        addResponder(node, answer, asked);
        node.start();
        node.send(REQUESTER, new Num(1));
        Await.until("the request reached the responder", () -> asked.size() == 1);
        return node;
    }

    @Test
    void shouldHoldOnlyOnceTheReplyInFlightHasReachedTheComponent() throws Exception {
        try (var node = requestInFlight("quiescent")) {

            var seenAtHold = new CompletableFuture<List<String>>();
            CompletableFuture<Void> held = node.holdAsync(REQUESTER, Duration.ofSeconds(30));
            held.thenRun(() -> seenAtHold.complete(List.copyOf(outcomes)));
            // The component is idle, but waits for its reply: it is not held, and runs on.
            node.send(REQUESTER, new Num(2));
            Await.until("a message while the hold waits is handled", () -> handled.size() == 2);
            assertFalse(held.isDone(), "held while a reply was in flight");

            answer.countDown();
            assertEquals(List.of("reply 1", "reply 2"), seenAtHold.get(30, TimeUnit.SECONDS).stream().sorted().toList(),
                    "both replies reached the component before the hold");
            node.send(REQUESTER, new Num(3));
            node.release(REQUESTER);
            Await.until("the message sent during the hold, after the release", () -> handled.size() == 3);
        }
    }

    @Test
    void shouldHoldAnywayWhenTheSettleWaitEndsWithTheReplyStillAwaited() throws Exception {
        try (var node = requestInFlight("quiescent-late")) {

            // No boundary comes after the wait ends (the component is idle): the wait's timer holds it.
            node.holdAsync(REQUESTER, Duration.ofMillis(100)).get(30, TimeUnit.SECONDS);
            assertEquals(List.of(), outcomes, "held with its request still in flight");
            answer.countDown();
            node.release(REQUESTER);
            Await.until("the late reply reaches the component after the release", () -> outcomes.size() == 1);
        }
    }

    @Test
    void shouldHoldAnIdleComponentWithoutRequestsAtOnceAndRefuseANegativeWait() throws Exception {
        try (var node = EtherwareNode.builder().nodeId("quiescent-idle").build()) {
            addRequester(node, outcomes, handled);
            node.start();
            CompletableFuture<Void> held = node.holdAsync(REQUESTER, Duration.ofSeconds(30));
            assertTrue(held.isDone(), "an idle component awaiting nothing is held on the calling thread");
            node.release(REQUESTER);
            assertThrows(IllegalArgumentException.class, () -> node.holdAsync(REQUESTER, Duration.ofMillis(-1)));
        }
    }

    @Test
    void shouldSwapOnlyOnceTheReplyInFlightHasReachedTheOldLogic() throws Exception {
        try (var node = requestInFlight("quiescent-swap")) {
            var newLogicSaw = new CopyOnWriteArrayList<Long>();
            CompletableFuture<SwapTimings> swapped = node.swapAsync(REQUESTER, () -> (message, context) ->
                    newLogicSaw.add(message.contentsAs(Num.class).value()), ns -> { }, Duration.ofSeconds(30));
            node.send(REQUESTER, new Num(2)); // the old logic runs on while its reply is awaited
            Await.until("a message while the swap waits is handled by the old logic", () -> handled.size() == 2);
            assertFalse(swapped.isDone(), "swapped while a reply was in flight");

            answer.countDown();
            swapped.get(30, TimeUnit.SECONDS);
            assertEquals(List.of("reply 1", "reply 2"), outcomes.stream().sorted().toList(),
                    "both replies reached the old logic's callbacks");
            node.send(REQUESTER, new Num(3));
            Await.until("the new logic handles what comes next", () -> newLogicSaw.equals(List.of(3L)));
            assertThrows(IllegalArgumentException.class, () -> node.swapAsync(REQUESTER,
                    () -> (message, context) -> { }, ns -> { }, Duration.ofMillis(-1)));
        }
    }

    @Test
    void shouldRunTwoSwapsThatWaitForQuiescenceInTheOrderTheyWereAsked() throws Exception {
        try (var node = requestInFlight("quiescent-two-swaps")) {
            var order = new CopyOnWriteArrayList<String>();
            CompletableFuture<SwapTimings> first = node.swapAsync(REQUESTER, () -> (message, context) -> { },
                    ns -> { }, Duration.ofSeconds(30));
            first.thenRun(() -> order.add("first"));
            CompletableFuture<SwapTimings> second = node.swapAsync(REQUESTER,
                    () -> (message, context) -> order.add("second's logic"), ns -> { }, Duration.ofSeconds(30));
            second.thenRun(() -> order.add("second"));
            answer.countDown();
            second.get(30, TimeUnit.SECONDS);
            assertTrue(first.isDone(), "the first swap ran before the second");
            node.send(REQUESTER, new Num(2));
            Await.until("the component handles with the second swap's logic", () -> order.size() == 3);
            assertEquals(List.of("first", "second", "second's logic"), order);
        }
    }

    /** One dispatcher, its thread held by a blocker's handling, a message for {@code REQUESTER} queued behind it. */
    private EtherwareNode queuedBehindABlocker(String nodeId, CountDownLatch unblock) {
        var node = EtherwareNode.builder().nodeId(nodeId).scheduler(() -> MultiDispatcherScheduler.roundRobin(1))
                .build();
        var blocking = new CountDownLatch(1);
        node.add(Profile.of("blocker"), () -> (message, context) -> {
            blocking.countDown();
            unblock.await(30, TimeUnit.SECONDS);
        });
        node.add(REQUESTER, () -> (message, context) -> handled.add(message.contentsAs(Num.class).value()));
        node.start();
        node.send(Profile.of("blocker"), new Num(0));
        Await.until("the blocker holds the one dispatcher", () -> blocking.getCount() == 0);
        node.send(REQUESTER, new Num(1));
        return node;
    }

    @Test
    void shouldHoldOnlyOnceTheMessageOfAnotherComponentQueuedAtTheHoldIsHandled() throws Exception {
        var unblock = new CountDownLatch(1);
        try (var node = queuedBehindABlocker("quiescent-queued", unblock)) {
            var seenAtHold = new CompletableFuture<List<Long>>();
            CompletableFuture<Void> held = node.holdAsync(REQUESTER, Duration.ofSeconds(30));
            held.thenRun(() -> seenAtHold.complete(List.copyOf(handled)));
            assertFalse(held.isDone(), "held (idle, awaiting nothing) with a message queued for it");
            unblock.countDown();
            assertEquals(List.of(1L), seenAtHold.get(30, TimeUnit.SECONDS), "the queued message was handled first");
            node.send(REQUESTER, new Num(2));
            node.release(REQUESTER);
            Await.until("the message sent during the hold, after the release", () -> handled.size() == 2);
        }
    }

    @Test
    void shouldSwapWithoutWaitingForTheMessagesQueuedForTheComponent() throws Exception {
        var unblock = new CountDownLatch(1);
        try (var node = queuedBehindABlocker("quiescent-queued-swap", unblock)) {
            var newLogicSaw = new CopyOnWriteArrayList<Long>();
            CompletableFuture<SwapTimings> swapped = node.swapAsync(REQUESTER, () -> (message, context) ->
                    newLogicSaw.add(message.contentsAs(Num.class).value()), ns -> { }, Duration.ofSeconds(30));
            assertTrue(swapped.isDone(), "an idle component awaiting no outcome is swapped at once");
            unblock.countDown();
            Await.until("the new logic handles the message queued before the swap",
                    () -> newLogicSaw.equals(List.of(1L)));
            assertEquals(List.of(), handled);
        }
    }

    @Test
    void shouldHoldAComponentThatKeepsSendingItselfMessagesWithoutWaitingOutTheSettleWait() throws Exception {
        try (var node = EtherwareNode.builder().nodeId("quiescent-self").build()) {
            node.add(REQUESTER, () -> (message, context) -> {
                long value = message.contentsAs(Num.class).value();
                handled.add(value);
                Thread.sleep(1);
                context.send(context.self(), new Num(value + 1), QoS.of(Criticality.LOW));
            });
            node.start();
            node.send(REQUESTER, new Num(1));
            Await.until("the component keeps itself going", () -> handled.size() >= 3);
            // Its own next message is always queued; it is quiescent at each boundary all the same.
            node.holdAsync(REQUESTER, Duration.ofSeconds(60)).get(20, TimeUnit.SECONDS);
            int atHold = handled.size();
            Thread.sleep(50);
            assertEquals(atHold, handled.size(), "handled after the hold");
            node.release(REQUESTER);
            Await.until("it goes on after the release", () -> handled.size() > atHold + 2);
        }
    }

    @Test
    void shouldFailAHoldStillWaitingWhenTheComponentIsRemoved() throws Exception {
        var unblock = new CountDownLatch(1);
        try (var node = queuedBehindABlocker("quiescent-removed", unblock)) {
            CompletableFuture<Void> held = node.holdAsync(REQUESTER, Duration.ofSeconds(30));
            assertFalse(held.isDone(), "held with a message queued for it");
            node.remove(REQUESTER);
            unblock.countDown();
            var failure = assertThrows(java.util.concurrent.ExecutionException.class,
                    () -> held.get(30, TimeUnit.SECONDS));
            assertTrue(failure.getCause() instanceof IllegalStateException, () -> "failed with " + failure.getCause());
        }
    }
}
