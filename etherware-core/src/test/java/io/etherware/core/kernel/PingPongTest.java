package io.etherware.core.kernel;

import static org.junit.jupiter.api.Assertions.assertEquals;

import io.etherware.core.component.Component;
import io.etherware.core.component.ComponentContext;
import io.etherware.core.component.Shell;
import io.etherware.core.message.Message;
import io.etherware.core.message.Profile;
import io.etherware.core.testing.Await;
import io.etherware.core.testing.ManualClock;
import io.etherware.core.testing.Num;
import java.util.concurrent.CompletableFuture;
import java.util.concurrent.TimeUnit;
import java.util.concurrent.atomic.AtomicLong;
import org.junit.jupiter.api.Test;

class PingPongTest {

    private static final long ROUNDS = 100_000;
    private static final Profile PING = Profile.of("ping");
    private static final Profile PONG = Profile.of("pong");

    @Test
    void shouldDeliverAllMessagesInOrderWhenTwoComponentsPlayPingPong() throws Exception {
        var done = new CompletableFuture<Long>();
        var outOfOrder = new AtomicLong();
        var pongSeen = new AtomicLong();
        try (var node = EtherwareNode.builder().nodeId("pingpong").build()) {
            node.add(PONG, () -> (message, context) -> {
                long value = message.contentsAs(Num.class).value();
                if (value != pongSeen.getAndIncrement()) {
                    outOfOrder.incrementAndGet();
                }
                context.reply(message, message.contents());
            });
            node.add(PING, () -> new Component() {
                private long expected;

                @Override
                public void onStart(ComponentContext context) {
                    context.send(PONG, new Num(0));
                }

                @Override
                public void onMessage(Message message, ComponentContext context) {
                    long value = message.contentsAs(Num.class).value();
                    if (value != expected) {
                        outOfOrder.incrementAndGet();
                    }
                    expected = value + 1;
                    if (expected < ROUNDS) {
                        context.send(PONG, new Num(expected));
                    } else {
                        done.complete(expected);
                    }
                }
            });
            node.start();

            assertEquals(ROUNDS, done.get(60, TimeUnit.SECONDS));
            assertEquals(0, outOfOrder.get(), "messages out of order");
            assertEquals(ROUNDS, pongSeen.get());
            // The last handling completes 'done' before it is counted: counters may lag by one.
            Await.until("the last handling is counted", () -> node.stats().handled() == 2 * ROUNDS);
            assertEquals(ROUNDS, node.shell(PONG).handledCount());
            NodeStats stats = node.stats();
            assertEquals(2 * ROUNDS, stats.handled());
            assertEquals(0, stats.undeliverable() + stats.discarded() + stats.failed());
        }
    }

    @Test
    void shouldDeliverABurstInSendOrderWhenOneComponentFloodsAnother() throws Exception {
        var received = new AtomicLong();
        var outOfOrder = new AtomicLong();
        // Only PONG's handling moves the node's clock, by 7 + value ns: the shell must report
        // exactly 7 + (ROUNDS - 1) ns for its last handling (not the first's 7, not a wall time).
        var clock = new ManualClock();
        Shell pong;
        try (var node = EtherwareNode.builder().nodeId("burst").clock(clock).build()) {
            pong = node.add(PONG, () -> (message, context) -> {
                long value = message.contentsAs(Num.class).value();
                clock.advance(7 + value);
                if (value != received.getAndIncrement()) {
                    outOfOrder.incrementAndGet();
                }
            });
            node.add(PING, () -> new Component() {
                @Override
                public void onStart(ComponentContext context) {
                    for (long i = 0; i < ROUNDS; i++) {
                        context.send(PONG, new Num(i));
                    }
                }

                @Override
                public void onMessage(Message message, ComponentContext context) {
                }
            });
            node.start();
            Await.until("all burst messages", () -> received.get() == ROUNDS);
            assertEquals(0, outOfOrder.get());
        }
        // Read after close, when the dispatcher has ended: the last handling's duration is recorded
        // after the handler returns.
        assertEquals(ROUNDS, pong.handledCount());
        assertEquals(7 + (ROUNDS - 1), pong.lastHandlingNs(), "the last handling's duration on the node's clock");
    }
}
