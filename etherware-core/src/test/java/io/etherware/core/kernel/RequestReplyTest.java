package io.etherware.core.kernel;

import static org.junit.jupiter.api.Assertions.assertEquals;
import static org.junit.jupiter.api.Assertions.assertFalse;
import static org.junit.jupiter.api.Assertions.assertInstanceOf;
import static org.junit.jupiter.api.Assertions.assertNotNull;
import static org.junit.jupiter.api.Assertions.assertThrows;
import static org.junit.jupiter.api.Assertions.assertTrue;

import io.etherware.core.component.Component;
import io.etherware.core.component.ComponentContext;
import io.etherware.core.component.RequestFailedException;
import io.etherware.core.component.RequestFailedException.Reason;
import io.etherware.core.kernel.internal.DispatcherMark;
import io.etherware.core.message.Message;
import io.etherware.core.message.Profile;
import io.etherware.core.message.QoS;
import io.etherware.core.message.Text;
import io.etherware.core.testing.Await;
import io.etherware.core.testing.Num;
import java.time.Duration;
import java.util.concurrent.CompletableFuture;
import java.util.concurrent.CountDownLatch;
import java.util.concurrent.ExecutionException;
import java.util.concurrent.LinkedBlockingQueue;
import java.util.concurrent.TimeUnit;
import java.util.concurrent.atomic.AtomicBoolean;
import java.util.concurrent.atomic.AtomicReference;
import org.junit.jupiter.api.Test;

class RequestReplyTest {

    private static final Profile ECHO = Profile.of("echo");
    private static final Profile CLIENT = Profile.of("client");
    private static final long SHORT_TIMEOUT_NS = TimeUnit.MILLISECONDS.toNanos(100);

    private static EtherwareNode node(String id) {
        return EtherwareNode.builder().nodeId(id).build();
    }

    private static Component echo() {
        return (message, context) -> context.reply(message, message.contents());
    }

    private static RequestFailedException failureOf(CompletableFuture<Message> future) {
        var error = assertThrows(ExecutionException.class, () -> future.get(30, TimeUnit.SECONDS));
        return assertInstanceOf(RequestFailedException.class, error.getCause());
    }

    @Test
    void shouldReturnTheReplyWhenRequestingFromOutside() {
        try (var node = node("rr-outside")) {
            node.add(ECHO, RequestReplyTest::echo);
            node.start();
            Message reply = node.requestBlocking(ECHO, new Text("hello"));
            assertEquals(new Text("hello"), reply.contents());
            assertNotNull(reply.correlationId());
            assertEquals(node.profile(), reply.profile());
        }
    }

    @Test
    void shouldCompleteAComponentsRequestOnItsOwnTurnWhenTheReplyArrives() throws Exception {
        var result = new CompletableFuture<String>();
        var inside = new AtomicBoolean();
        try (var node = node("rr-turn")) {
            node.add(ECHO, RequestReplyTest::echo);
            node.add(CLIENT, () -> new Component() {
                private int replies; // touched only within the component's turn

                @Override
                public void onMessage(Message message, ComponentContext context) {
                    inside.set(true);
                    context.request(ECHO, new Num(7)).thenAccept(reply -> {
                        replies++;
                        // The continuation runs in the client's own turn, on a dispatcher.
                        result.complete(reply.contentsAs(Num.class).value() + "/" + replies + "/"
                                + DispatcherMark.isDispatcherThread());
                    });
                    inside.set(false);
                }
            });
            node.start();
            node.send(CLIENT, new Text("go"));
            assertEquals("7/1/true", result.get(30, TimeUnit.SECONDS));
            assertFalse(inside.get());
        }
    }

    @Test
    void shouldSendAnUndeliverableNoticeToTheSenderWhenTheProfileIsUnknown() throws Exception {
        var notices = new LinkedBlockingQueue<Message>();
        try (var node = node("rr-unknown")) {
            node.add(CLIENT, () -> new Component() {
                @Override
                public void onStart(ComponentContext context) {
                    context.send(Profile.of("nobody", "car", "9"), new Text("hello?"));
                }

                @Override
                public void onMessage(Message message, ComponentContext context) {
                    notices.add(message);
                }
            });
            node.start();
            Message notice = notices.poll(30, TimeUnit.SECONDS);
            assertNotNull(notice, "the sender must be told");
            var undeliverable = notice.contentsAs(Undeliverable.class);
            assertEquals("nobody[car=9]", undeliverable.profile());
            assertTrue(undeliverable.reason().contains("no component matches profile 'nobody[car=9]'"),
                    undeliverable.reason());
            assertEquals(undeliverable.messageId(), notice.correlationId().toString());
            assertEquals(node.profile(), notice.sender());
            assertEquals(1, node.stats().undeliverable());
        }
    }

    @Test
    void shouldCountAnUndeliverableMessageWhenItHasNoSender() {
        try (var node = node("rr-unknown-outside")) {
            node.start();
            node.send(Profile.of("nobody"), new Text("lost"));
            assertEquals(1, node.stats().undeliverable());
        }
    }

    @Test
    void shouldFailTheRequestWhenTheProfileIsUnknown() {
        try (var node = node("rr-unknown-request")) {
            node.start();
            var failure = failureOf(node.request(Profile.of("nobody"), new Text("?")));
            assertEquals(Reason.UNDELIVERABLE, failure.reason());
            assertTrue(failure.getMessage().contains("nobody"), failure.getMessage());
            assertEquals(1, node.stats().undeliverable());
        }
    }

    @Test
    void shouldNameTheCandidatesWhenAQueryIsAmbiguous() {
        try (var node = node("rr-ambiguous")) {
            node.add(Profile.of("controller", "car", "1"), RequestReplyTest::echo);
            node.add(Profile.of("controller", "car", "2"), RequestReplyTest::echo);
            node.start();

            var error = assertThrows(ProfileResolutionException.class,
                    () -> node.registry().resolve(Profile.of("controller")));
            assertTrue(error.getMessage().contains("ambiguous"), error.getMessage());
            assertTrue(error.getMessage().contains("'controller[car=1]'"), error.getMessage());
            assertTrue(error.getMessage().contains("'controller[car=2]'"), error.getMessage());
            assertEquals(2, error.candidates().size());

            var failure = failureOf(node.request(Profile.of("controller"), new Text("?")));
            assertEquals(Reason.UNDELIVERABLE, failure.reason());
            assertTrue(failure.getMessage().contains("controller[car=1]")
                    && failure.getMessage().contains("controller[car=2]"), failure.getMessage());

            // A query that matches exactly one profile resolves.
            Message reply = node.requestBlocking(Profile.of("controller", "car", "2"), new Text("two"));
            assertEquals(new Text("two"), reply.contents());
        }
    }

    @Test
    void shouldResolveAQueryThatMatchesExactlyOneComponent() {
        try (var node = node("rr-query")) {
            node.add(Profile.of("plant", "room", "1", "sensor", "t"), RequestReplyTest::echo);
            node.start();
            Message reply = node.requestBlocking(Profile.of("plant"), new Text("q"));
            assertEquals(new Text("q"), reply.contents());
            assertEquals(Profile.of("plant", "room", "1", "sensor", "t"), reply.sender());
        }
    }

    @Test
    void shouldFailWithTimeoutWhenNoReplyComes() {
        try (var node = node("rr-timeout")) {
            node.add(ECHO, () -> (message, context) -> { });
            node.start();
            long startNs = System.nanoTime();
            var failure = failureOf(node.request(ECHO, new Text("?"), QoS.NONE, SHORT_TIMEOUT_NS));
            long elapsedNs = System.nanoTime() - startNs;
            assertEquals(Reason.TIMEOUT, failure.reason());
            assertTrue(failure.getMessage().contains("within 100 ms"), failure.getMessage());
            assertTrue(elapsedNs >= SHORT_TIMEOUT_NS, "not before the timeout");
            assertEquals(1, node.stats().requestTimeouts());
        }
    }

    @Test
    void shouldCountAndDropALateReply() throws Exception {
        var holdReply = new CountDownLatch(1);
        var replied = new CountDownLatch(1);
        var clientMessages = new LinkedBlockingQueue<Message>();
        var outcome = new AtomicReference<Throwable>();
        try (var node = node("rr-late")) {
            node.add(ECHO, () -> (message, context) -> {
                // Reply from another thread after the requester gave up.
                Thread.ofPlatform().start(() -> {
                    try {
                        holdReply.await(30, TimeUnit.SECONDS);
                    } catch (InterruptedException e) {
                        return;
                    }
                    context.reply(message, new Text("too late"));
                    replied.countDown();
                });
            });
            node.add(CLIENT, () -> new Component() {
                @Override
                public void onStart(ComponentContext context) {
                    context.request(ECHO, new Text("?"), QoS.NONE, SHORT_TIMEOUT_NS)
                            .whenComplete((reply, error) -> outcome.set(error));
                }

                @Override
                public void onMessage(Message message, ComponentContext context) {
                    clientMessages.add(message);
                }
            });
            node.start();
            Await.until("the request times out", () -> node.stats().requestTimeouts() == 1);
            holdReply.countDown();
            assertTrue(replied.await(30, TimeUnit.SECONDS));
            Await.until("the late reply is counted", () -> node.stats().lateReplies() == 1);
            Await.until("the requester learns of the timeout", () -> outcome.get() != null);
            assertEquals(Reason.TIMEOUT, ((RequestFailedException) outcome.get()).reason());
            // A message sent to the client after the late reply arrives after it (one FIFO queue).
            node.send(CLIENT, new Text("marker"));
            Message first = clientMessages.poll(30, TimeUnit.SECONDS);
            assertEquals(new Text("marker"), first.contents(), "the late reply must not reach onMessage");
        }
    }

    @Test
    void shouldFailTheRequestNamingTheCauseWhenTheResponderThrows() {
        try (var node = EtherwareNode.builder().nodeId("rr-throws")
                .supervision(SupervisionPolicy.fresh(10, Duration.ofMinutes(1))).build()) {
            node.add(ECHO, () -> (message, context) -> {
                throw new IllegalStateException("sensor saturated");
            });
            node.start();
            var failure = failureOf(node.request(ECHO, new Text("?")));
            assertEquals(Reason.RESPONDER_FAILED, failure.reason());
            assertTrue(failure.getMessage().contains("responder 'echo'"), failure.getMessage());
            assertTrue(failure.getMessage().contains("IllegalStateException: sensor saturated"), failure.getMessage());
            Await.until("the failure is counted", () -> node.stats().failed() == 1);
            assertEquals(1, node.stats().restarts());
        }
    }

    @Test
    void shouldRefuseABlockingRequestOnADispatcherThread() throws Exception {
        var refusal = new CompletableFuture<Throwable>();
        try (var node = node("rr-blocking")) {
            node.add(ECHO, RequestReplyTest::echo);
            node.add(CLIENT, () -> (message, context) -> {
                try {
                    context.requestBlocking(ECHO, new Text("?"), QoS.NONE, SHORT_TIMEOUT_NS);
                    refusal.complete(null);
                } catch (IllegalStateException e) {
                    refusal.complete(e);
                }
            });
            node.start();
            node.send(CLIENT, new Text("go"));
            Throwable error = refusal.get(30, TimeUnit.SECONDS);
            assertNotNull(error, "requestBlocking must refuse a dispatcher thread");
            assertTrue(error.getMessage().contains("requestBlocking was called on dispatcher thread"), error.getMessage());
            assertTrue(error.getMessage().contains("deadlock"), error.getMessage());
        }
    }

    @Test
    void shouldAllowABlockingRequestInOnStartAtNodeStart() {
        var reply = new AtomicReference<Message>();
        try (var node = node("rr-blocking-start")) {
            node.add(ECHO, RequestReplyTest::echo);
            node.add(CLIENT, () -> new Component() {
                @Override
                public void onStart(ComponentContext context) {
                    reply.set(context.requestBlocking(ECHO, new Text("boot"), QoS.NONE, TimeUnit.SECONDS.toNanos(30)));
                }

                @Override
                public void onMessage(Message message, ComponentContext context) {
                }
            });
            node.start();
            assertEquals(new Text("boot"), reply.get().contents());
        }
    }

    @Test
    void shouldRefuseSendingBeforeTheNodeStarts() {
        try (var node = node("rr-not-started")) {
            var error = assertThrows(IllegalStateException.class, () -> node.send(ECHO, new Text("early")));
            assertTrue(error.getMessage().contains("call start()"), error.getMessage());
        }
    }
}
