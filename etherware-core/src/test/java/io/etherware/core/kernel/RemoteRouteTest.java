package io.etherware.core.kernel;

import static org.junit.jupiter.api.Assertions.assertEquals;
import static org.junit.jupiter.api.Assertions.assertInstanceOf;
import static org.junit.jupiter.api.Assertions.assertThrows;
import static org.junit.jupiter.api.Assertions.assertTrue;

import io.etherware.core.component.Component;
import io.etherware.core.component.ComponentContext;
import io.etherware.core.component.RequestFailedException;
import io.etherware.core.message.Message;
import io.etherware.core.message.Profile;
import io.etherware.core.message.Text;
import io.etherware.core.testing.Await;
import io.etherware.core.testing.Num;
import java.util.List;
import java.util.concurrent.ExecutionException;
import java.util.concurrent.ExecutorService;
import java.util.concurrent.Executors;
import java.util.concurrent.LinkedBlockingQueue;
import java.util.concurrent.TimeUnit;
import org.junit.jupiter.api.AfterEach;
import org.junit.jupiter.api.BeforeEach;
import org.junit.jupiter.api.Test;

/**
 * Two nodes in one JVM joined by a fake transport: each direction is one thread that hands
 * messages to the other node's kernel, as a NetworkMessenger will (minus the XML and TCP).
 */
class RemoteRouteTest {

    private static final Profile ECHO = Profile.of("echo", "node", "b");
    private static final Profile CLIENT = Profile.of("client", "node", "a");

    private EtherwareNode nodeA;
    private EtherwareNode nodeB;
    private ExecutorService wireAtoB;
    private ExecutorService wireBtoA;

    /** A route that queues the message on a wire thread, like a transport's send queue. */
    private static RemoteRoute over(ExecutorService wire, Kernel to) {
        return message -> wire.execute(() -> to.send(message));
    }

    @BeforeEach
    void joinTwoNodes() {
        nodeA = EtherwareNode.builder().nodeId("a").build();
        nodeB = EtherwareNode.builder().nodeId("b").build();
        wireAtoB = Executors.newSingleThreadExecutor();
        wireBtoA = Executors.newSingleThreadExecutor();
        nodeA.registry().registerRemote(ECHO, over(wireAtoB, nodeB));
        nodeB.registry().registerRemote(CLIENT, over(wireBtoA, nodeA));
        nodeB.registry().registerRemote(nodeA.profile(), over(wireBtoA, nodeA));
    }

    @AfterEach
    void close() {
        nodeA.close();
        nodeB.close();
        wireAtoB.shutdownNow();
        wireBtoA.shutdownNow();
    }

    @Test
    void shouldDeliverToARemoteProfileAndBringTheReplyBackThroughTheSameSend() throws Exception {
        var replies = new LinkedBlockingQueue<Message>();
        nodeB.add(ECHO, () -> (message, context) -> context.reply(message, message.contents()));
        nodeA.add(CLIENT, () -> new Component() {
            @Override
            public void onStart(ComponentContext context) {
                context.send(Profile.of("echo"), new Num(42)); // a query, resolved to the route
            }

            @Override
            public void onMessage(Message message, ComponentContext context) {
                replies.add(message);
            }
        });
        nodeB.start();
        nodeA.start();
        Message reply = replies.poll(30, TimeUnit.SECONDS);
        assertEquals(new Num(42), reply.contents());
        assertEquals(ECHO, reply.sender());
        assertEquals("a", reply.correlationId().nodeId());
        Await.until("the echo's handling is counted", () -> nodeB.shell(ECHO).handledCount() == 1);
    }

    @Test
    void shouldCompleteARequestAcrossNodes() {
        nodeB.add(ECHO, () -> (message, context) -> context.reply(message, new Text("pong from b")));
        nodeB.start();
        nodeA.start();
        Message reply = nodeA.requestBlocking(ECHO, new Text("ping"));
        assertEquals(new Text("pong from b"), reply.contents());
    }

    @Test
    void shouldFailARemoteRequestNamingTheCauseWhenTheRemoteResponderThrows() {
        nodeB.add(ECHO, () -> (message, context) -> {
            throw new ArithmeticException("division by zero in the model");
        });
        nodeB.start();
        nodeA.start();
        var error = assertThrows(ExecutionException.class,
                () -> nodeA.request(ECHO, new Text("?")).get(30, TimeUnit.SECONDS));
        var failure = assertInstanceOf(RequestFailedException.class, error.getCause());
        assertEquals(RequestFailedException.Reason.RESPONDER_FAILED, failure.reason());
        assertTrue(failure.getMessage().contains("division by zero in the model"), failure.getMessage());
    }

    @Test
    void shouldReportUndeliverableWhenTheRouteRefuses() throws Exception {
        var notices = new LinkedBlockingQueue<Message>();
        nodeA.registry().registerRemote(Profile.of("down"), message -> {
            throw new IllegalStateException("link to node c is down");
        });
        nodeA.add(CLIENT, () -> new Component() {
            @Override
            public void onStart(ComponentContext context) {
                context.send(Profile.of("down"), new Text("?"));
            }

            @Override
            public void onMessage(Message message, ComponentContext context) {
                notices.add(message);
            }
        });
        nodeA.start();
        var notice = assertInstanceOf(Undeliverable.class, notices.poll(30, TimeUnit.SECONDS).contents());
        assertTrue(notice.reason().contains("link to node c is down"), notice.reason());
        assertEquals(1, nodeA.stats().undeliverable());
    }

    @Test
    void shouldRefuseToUnregisterALocalComponentAsARoute() {
        nodeB.add(ECHO, () -> (message, context) -> { });
        var error = assertThrows(IllegalArgumentException.class, () -> nodeB.registry().unregisterRemote(ECHO));
        assertTrue(error.getMessage().contains("local component"), error.getMessage());
        assertTrue(nodeA.registry().unregisterRemote(ECHO));
        assertEquals(false, nodeA.registry().unregisterRemote(ECHO));
    }

    @Test
    void shouldLetALocalComponentDisplaceARemoteRouteAndTellTheRegistryListener() {
        var changes = new LinkedBlockingQueue<String>();
        nodeA.registry().addListener((profile, before, after) -> changes.add(profile + ": "
                + (before == null ? "none" : before.getClass().getSimpleName()) + " -> "
                + (after == null ? "none" : after.getClass().getSimpleName())));
        nodeA.start();
        nodeA.add(ECHO, () -> (message, context) -> context.reply(message, new Text("local echo")));
        assertEquals(new Text("local echo"), nodeA.requestBlocking(ECHO, new Text("?")).contents());
        var error = assertThrows(IllegalArgumentException.class,
                () -> nodeA.registry().registerRemote(ECHO, message -> { }));
        assertTrue(error.getMessage().contains("a local component"), error.getMessage());
        nodeA.remove(ECHO);
        assertEquals(List.of("echo[node=b]: Remote -> Local", "echo[node=b]: Local -> none"), List.copyOf(changes));
    }
}
