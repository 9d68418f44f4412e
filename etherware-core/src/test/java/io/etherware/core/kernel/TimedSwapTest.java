package io.etherware.core.kernel;

import static org.junit.jupiter.api.Assertions.assertEquals;
import static org.junit.jupiter.api.Assertions.assertFalse;
import static org.junit.jupiter.api.Assertions.assertInstanceOf;
import static org.junit.jupiter.api.Assertions.assertThrows;
import static org.junit.jupiter.api.Assertions.assertTrue;

import io.etherware.core.component.Component;
import io.etherware.core.component.ComponentContext;
import io.etherware.core.component.ComponentState;
import io.etherware.core.message.Message;
import io.etherware.core.message.Profile;
import io.etherware.core.testing.Await;
import io.etherware.core.testing.Num;
import java.util.List;
import java.util.concurrent.CompletableFuture;
import java.util.concurrent.CopyOnWriteArrayList;
import java.util.concurrent.ExecutionException;
import java.util.concurrent.TimeUnit;
import java.util.concurrent.atomic.AtomicLong;
import org.junit.jupiter.api.Test;

/** The timed swap: its timings, and the one call that reports the new logic's first message. */
class TimedSwapTest {

    private static final Profile TARGET = Profile.of("target");

    /** State with a raised schema version, to see it reported. */
    record CountV3(long count) implements ComponentState {
        @Override
        public int schemaVersion() {
            return 3;
        }
    }

    /** Records the clock when each handling begins and ends; its count is its state. */
    static class Stamping implements Component {
        final String version;
        final List<String> log;
        final List<long[]> stamps;
        long count;

        Stamping(String version, List<String> log, List<long[]> stamps) {
            this.version = version;
            this.log = log;
            this.stamps = stamps;
        }

        @Override
        public void onMessage(Message message, ComponentContext context) {
            long beginNs = System.nanoTime();
            count++;
            log.add(version + ":" + count);
            stamps.add(new long[] {beginNs, System.nanoTime()});
        }

        @Override
        public ComponentState snapshot() {
            return new CountV3(count);
        }

        @Override
        public void restore(ComponentState state) {
            count = ((CountV3) state).count();
        }
    }

    @Test
    void shouldReportTheGapBetweenTheOldLogicsLastMessageAndTheNewLogicsFirstWhenSwapped() throws Exception {
        var log = new CopyOnWriteArrayList<String>();
        var oldStamps = new CopyOnWriteArrayList<long[]>();
        var newStamps = new CopyOnWriteArrayList<long[]>();
        var firstStarts = new CopyOnWriteArrayList<Long>();
        try (var node = EtherwareNode.builder().nodeId("timed-swap").build()) {
            node.add(TARGET, () -> new Stamping("v1", log, oldStamps));
            node.start();
            for (int i = 0; i < 3; i++) {
                node.send(TARGET, new Num(i));
            }
            Await.until("three messages for v1", () -> log.size() == 3);

            SwapTimings timings = node.swapAsync(TARGET, () -> new Stamping("v2", log, newStamps), firstStarts::add)
                    .get(30, TimeUnit.SECONDS);
            assertEquals(3, timings.stateSchemaVersion());
            assertTrue(timings.lastOldHandlingEndNs() >= oldStamps.getLast()[1],
                    "the old logic's last handling ended after its handler returned");
            assertTrue(timings.swapStartNs() >= timings.lastOldHandlingEndNs());
            assertTrue(timings.swapEndNs() >= timings.swapStartNs());
            assertEquals(timings.swapEndNs() - timings.swapStartNs(), timings.pauseNs());
            assertEquals(List.of(), firstStarts, "no message has reached the new logic yet");

            node.send(TARGET, new Num(3));
            node.send(TARGET, new Num(4));
            Await.until("two messages for v2", () -> newStamps.size() == 2);
            Await.until("the first-handling call", () -> firstStarts.size() == 1);
            assertEquals(List.of("v1:1", "v1:2", "v1:3", "v2:4", "v2:5"), log);
            long firstStartNs = firstStarts.getFirst();
            assertTrue(firstStartNs >= timings.swapEndNs(), "the new logic's first message began after the swap");
            assertTrue(firstStartNs <= newStamps.getFirst()[0], "the reported start precedes the handler's own clock");
            Thread.sleep(20); // a second call would come after the second message; none may
            assertEquals(1, firstStarts.size(), "told once");
        }
    }

    @Test
    void shouldReportNoLastHandlingWhenTheOldLogicHandledNothing() throws Exception {
        var firstStarts = new CopyOnWriteArrayList<Long>();
        try (var node = EtherwareNode.builder().nodeId("timed-swap-idle").build()) {
            node.add(TARGET, () -> (message, context) -> { });
            node.start();
            SwapTimings timings = node.swapAsync(TARGET, () -> (message, context) -> { }, firstStarts::add)
                    .get(30, TimeUnit.SECONDS);
            assertEquals(SwapTimings.UNKNOWN_NS, timings.lastOldHandlingEndNs());
            assertEquals(-1, timings.stateSchemaVersion(), "a stateless component hands over no state");
            node.send(TARGET, new Num(1));
            Await.until("the first-handling call", () -> firstStarts.size() == 1);
        }
    }

    @Test
    void shouldNeverReportAFirstHandlingWhenTheSwapRollsBack() throws Exception {
        var log = new CopyOnWriteArrayList<String>();
        var stamps = new CopyOnWriteArrayList<long[]>();
        var firstStarts = new AtomicLong();
        try (var node = EtherwareNode.builder().nodeId("timed-swap-rollback").build()) {
            node.add(TARGET, () -> new Stamping("v1", log, stamps));
            node.start();
            CompletableFuture<SwapTimings> swap = node.swapAsync(TARGET, () -> new Stamping("bad", log, stamps) {
                @Override
                public void restore(ComponentState state) {
                    throw new IllegalArgumentException("cannot read schema " + state.schemaVersion());
                }
            }, startNs -> firstStarts.incrementAndGet());
            var failure = assertThrows(ExecutionException.class, () -> swap.get(30, TimeUnit.SECONDS));
            assertInstanceOf(IllegalArgumentException.class, failure.getCause());
            assertEquals("cannot read schema 3", failure.getCause().getMessage());

            node.send(TARGET, new Num(1));
            Await.until("the old logic serves on", () -> log.size() == 1);
            assertEquals(List.of("v1:1"), log);
            assertEquals(0, firstStarts.get());
        }
    }
}
