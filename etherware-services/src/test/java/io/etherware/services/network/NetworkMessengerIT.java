package io.etherware.services.network;

import static org.junit.jupiter.api.Assertions.assertEquals;
import static org.junit.jupiter.api.Assertions.assertTrue;

import io.etherware.core.component.Component;
import io.etherware.core.component.ComponentContext;
import io.etherware.core.message.Criticality;
import io.etherware.core.message.Message;
import io.etherware.core.message.Profile;
import io.etherware.core.message.QoS;
import io.etherware.core.message.Text;
import io.etherware.testkit.Await;
import java.time.Duration;
import java.util.List;
import java.util.concurrent.LinkedBlockingQueue;
import java.util.concurrent.TimeUnit;
import org.junit.jupiter.api.Test;

/** Two nodes in one JVM over loopback TCP: requests, replies, announcements, QoS. */
class NetworkMessengerIT {

    private static final Profile ECHO = Profile.of("echo", "node", "b");

    @Test
    void shouldCompleteRequestsAcrossNodesFromOutsideAndFromAComponent() throws Exception {
        try (var b = TestNode.start("b", TestNode.config());
             var a = TestNode.start("a", TestNode.config().peer(b.address()))) {
            b.node.add(ECHO, () -> (message, context) -> context.reply(message, new Text("echo: "
                    + message.contentsAs(Text.class).text())));
            assertTrue(a.net.awaitResolvable(ECHO, Duration.ofSeconds(30)), "b's echo is announced to a");

            Message reply = a.node.requestBlocking(ECHO, new Text("ping"));
            assertEquals(new Text("echo: ping"), reply.contents());
            assertEquals(ECHO, reply.sender());

            var replies = new LinkedBlockingQueue<Message>();
            a.node.add(Profile.of("client", "node", "a"), () -> new Component() {
                @Override
                public void onStart(ComponentContext context) {
                    context.request(Profile.of("echo"), new Text("from a component"))
                            .thenAccept(replies::add);
                }

                @Override
                public void onMessage(Message message, ComponentContext context) {
                }
            });
            Message componentReply = replies.poll(30, TimeUnit.SECONDS);
            assertEquals(new Text("echo: from a component"), componentReply.contents());
        }
    }

    @Test
    void shouldPreserveTheQosOnTheReceivingNode() throws Exception {
        var seen = new LinkedBlockingQueue<Message>();
        try (var b = TestNode.start("b", TestNode.config());
             var a = TestNode.start("a", TestNode.config().peer(b.address()))) {
            b.node.add(Profile.of("sink"), () -> (message, context) -> seen.add(message));
            assertTrue(a.net.awaitResolvable(Profile.of("sink"), Duration.ofSeconds(30)));
            var qos = new QoS(Criticality.HIGH, 15_000_000, 12_000_000, 2_000_000);
            a.node.send(Profile.of("sink"), new Num(7), qos);
            Message arrived = seen.poll(30, TimeUnit.SECONDS);
            assertEquals(qos, arrived.qos());
            assertEquals(new Num(7), arrived.contents());
            assertEquals("a", arrived.messageId().nodeId());
        }
    }

    @Test
    void shouldRouteTheReplyToAComponentThatRequestsAsSoonAsItIsAdded() throws Exception {
        int components = 50;
        var replies = new LinkedBlockingQueue<Message>();
        var failures = new LinkedBlockingQueue<Throwable>();
        try (var b = TestNode.start("b", TestNode.config());
             var a = TestNode.start("a", TestNode.config().peer(b.address()))) {
            b.node.add(ECHO, () -> (message, context) -> context.reply(message, message.contents()));
            assertTrue(a.net.awaitResolvable(ECHO, Duration.ofSeconds(30)));
            for (int i = 0; i < components; i++) {
                // The announcement of the new profile must reach b before the request does, or
                // b cannot route the reply.
                a.node.add(Profile.of("client", "i", Integer.toString(i)), () -> new Component() {
                    @Override
                    public void onStart(ComponentContext context) {
                        context.request(ECHO, new Text(context.self().toString())).whenComplete((reply, error) -> {
                            if (error != null) {
                                failures.add(error);
                            } else {
                                replies.add(reply);
                            }
                        });
                    }

                    @Override
                    public void onMessage(Message message, ComponentContext context) {
                    }
                });
            }
            Await.until("every component has its reply or failure", () -> replies.size() + failures.size() == components);
            assertEquals(List.of(), List.copyOf(failures));
            assertEquals(0, b.node.stats().undeliverable());
        }
    }
}
