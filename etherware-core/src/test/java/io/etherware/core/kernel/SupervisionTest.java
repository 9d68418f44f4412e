package io.etherware.core.kernel;

import static org.junit.jupiter.api.Assertions.assertEquals;
import static org.junit.jupiter.api.Assertions.assertInstanceOf;
import static org.junit.jupiter.api.Assertions.assertTrue;

import io.etherware.core.component.Component;
import io.etherware.core.component.ComponentContext;
import io.etherware.core.component.ComponentState;
import io.etherware.core.component.Shell;
import io.etherware.core.message.Message;
import io.etherware.core.message.Profile;
import io.etherware.core.message.Text;
import io.etherware.core.testing.Await;
import io.etherware.core.testing.Counted;
import io.etherware.core.testing.ManualClock;
import io.etherware.core.testing.Num;
import java.time.Duration;
import java.util.List;
import java.util.concurrent.CopyOnWriteArrayList;
import java.util.concurrent.LinkedBlockingQueue;
import java.util.concurrent.TimeUnit;
import java.util.concurrent.atomic.AtomicInteger;
import java.util.stream.LongStream;
import org.junit.jupiter.api.Test;

/** The Management Tree: restart policies, intensity, escalation, start and stop order. */
class SupervisionTest {

    private static final Profile FRAGILE = Profile.of("fragile");
    private static final Profile BYSTANDER = Profile.of("bystander");

    /** Counts the messages it handled; throws on every value divisible by 3. Its count is its state. */
    static final class ThirdThrower implements Component {
        final List<Long> counts;
        long count;

        ThirdThrower(List<Long> counts) {
            this.counts = counts;
        }

        @Override
        public void onMessage(Message message, ComponentContext context) {
            long value = message.contentsAs(Num.class).value();
            count++; // changed before the failure: a restart must not keep this half-update
            if (value % 3 == 0) {
                throw new IllegalStateException("value " + value + " is divisible by 3");
            }
            counts.add(count);
        }

        @Override
        public ComponentState snapshot() {
            return new Counted(count);
        }

        @Override
        public void restore(ComponentState state) {
            count = ((Counted) state).count();
        }
    }

    private static void sendValues(EtherwareNode node, Profile to, long from, long toInclusive) {
        for (long value = from; value <= toInclusive; value++) {
            node.send(to, new Num(value));
        }
    }

    private static void awaitProcessed(Shell shell, long messages) {
        Await.until(messages + " messages processed by " + shell.profile(),
                () -> shell.handledCount() + shell.failedCount() == messages);
    }

    @Test
    void shouldRestartFromTheSnapshotAndCountExactlyWhenEveryThirdMessageThrows() {
        var counts = new CopyOnWriteArrayList<Long>();
        var bystanderSeen = new AtomicInteger();
        try (var node = EtherwareNode.builder().nodeId("sup-third").build()) {
            Shell fragile = node.add(FRAGILE, () -> new ThirdThrower(counts),
                    SupervisionPolicy.fromSnapshot(100, Duration.ofMinutes(1)));
            node.add(BYSTANDER, () -> (message, context) -> bystanderSeen.incrementAndGet());
            node.start();

            // 31 ends on a success, so when it is handled the 10th restart is complete too.
            sendValues(node, FRAGILE, 1, 31);
            awaitProcessed(fragile, 31);

            assertEquals(21, fragile.handledCount());
            assertEquals(10, fragile.failedCount());
            assertEquals(10, fragile.restartCount());
            assertEquals(Shell.State.RUNNING, fragile.state());
            // The counter continues across restarts: 1..21 without a gap or a reset.
            assertEquals(LongStream.rangeClosed(1, 21).boxed().toList(), counts);
            // The dispatcher survived.
            node.send(BYSTANDER, new Text("still there?"));
            Await.until("the bystander's message", () -> bystanderSeen.get() == 1);
            NodeStats stats = node.stats();
            assertEquals(10, stats.restarts());
            assertEquals(0, stats.escalations());
        }
    }

    @Test
    void shouldResetAllComponentsWhenTheRestartIntensityIsExceeded() {
        var fragileCounts = new CopyOnWriteArrayList<Long>();
        var bystanderCounts = new CopyOnWriteArrayList<Long>();
        try (var node = EtherwareNode.builder().nodeId("sup-reset").escalation(Escalation.RESET_ALL).build()) {
            Shell fragile = node.add(FRAGILE, () -> new ThirdThrower(fragileCounts),
                    SupervisionPolicy.fromSnapshot(3, Duration.ofMinutes(1)));
            Shell bystander = node.add(BYSTANDER, () -> new ThirdThrower(bystanderCounts));
            node.start();

            sendValues(node, BYSTANDER, 1, 2); // bystander count 2
            awaitProcessed(bystander, 2);
            sendValues(node, FRAGILE, 1, 12); // failures at 3, 6, 9 restart; 12 escalates
            awaitProcessed(fragile, 12);
            Await.until("the reset", () -> node.stats().resets() == 1);

            assertEquals(3, fragile.restartCount());
            assertEquals(4, fragile.failedCount());
            NodeStats stats = node.stats();
            assertEquals(1, stats.escalations());
            assertEquals(1, stats.resets());

            // Both components start fresh after the reset: their counters begin again at 1.
            node.send(FRAGILE, new Num(13));
            node.send(BYSTANDER, new Num(4));
            awaitProcessed(fragile, 13);
            awaitProcessed(bystander, 3);
            assertEquals(List.of(1L, 2L, 1L), bystanderCounts);
            assertEquals(1L, fragileCounts.getLast());
            assertEquals(Shell.State.RUNNING, fragile.state());
            assertEquals(Shell.State.RUNNING, bystander.state());
        }
    }

    @Test
    void shouldCountOnlyRestartsWithinTheWindowWhenCheckingTheIntensity() {
        var clock = new ManualClock();
        long secondNs = TimeUnit.SECONDS.toNanos(1);
        try (var node = EtherwareNode.builder().nodeId("sup-window").clock(clock).build()) {
            Shell fragile = node.add(FRAGILE, () -> new ThirdThrower(new CopyOnWriteArrayList<>()),
                    SupervisionPolicy.fromSnapshot(2, Duration.ofSeconds(10)));
            node.start();
            long[] failureTimesNs = {0, secondNs, 20 * secondNs, 20 * secondNs + secondNs / 2};
            for (int i = 0; i < failureTimesNs.length; i++) {
                clock.set(failureTimesNs[i]);
                node.send(FRAGILE, new Num(3));
                awaitProcessed(fragile, i + 1);
            }
            // Restarts at 0 s and 1 s; at 20 s and 20.5 s the older ones left the 10 s window.
            assertEquals(4, fragile.restartCount());
            assertEquals(0, node.stats().escalations());

            clock.set(21 * secondNs); // the last two restarts were 1 s ago: a third is too many
            node.send(FRAGILE, new Num(3));
            Await.until("the escalation", () -> node.stats().escalations() == 1);
            assertEquals(4, fragile.restartCount());
        }
    }

    @Test
    void shouldStopTheNodeWhenTheEscalationIsStopNode() throws Exception {
        var node = EtherwareNode.builder().nodeId("sup-stop-node").escalation(Escalation.STOP_NODE).build();
        Shell fragile = node.add(FRAGILE, () -> new ThirdThrower(new CopyOnWriteArrayList<>()),
                SupervisionPolicy.fresh(0, Duration.ofMinutes(1)));
        node.start();
        node.send(FRAGILE, new Num(3));
        node.closedFuture().get(30, TimeUnit.SECONDS);
        assertTrue(node.isClosed());
        assertEquals(1, node.stats().escalations());
        assertEquals(0, fragile.restartCount());
        assertEquals(Shell.State.STOPPED, fragile.state());
        node.close(); // idempotent
    }

    @Test
    void shouldStopTheComponentAndReportUndeliverableWhenThePolicyIsStop() throws Exception {
        var notices = new LinkedBlockingQueue<Message>();
        try (var node = EtherwareNode.builder().nodeId("sup-stop").build()) {
            Shell fragile = node.add(FRAGILE, () -> new ThirdThrower(new CopyOnWriteArrayList<>()),
                    SupervisionPolicy.stop());
            node.add(BYSTANDER, () -> new Component() {
                @Override
                public void onMessage(Message message, ComponentContext context) {
                    if (message.contents() instanceof Undeliverable) {
                        notices.add(message);
                    } else {
                        context.send(FRAGILE, new Num(1));
                    }
                }
            });
            node.start();
            node.send(FRAGILE, new Num(3));
            awaitProcessed(fragile, 1);
            Await.until("the component fails", () -> fragile.state() == Shell.State.FAILED);
            node.send(BYSTANDER, new Text("poke"));
            Message notice = notices.poll(30, TimeUnit.SECONDS);
            var undeliverable = assertInstanceOf(Undeliverable.class, notice.contents());
            assertTrue(undeliverable.reason().contains("component 'fragile' is FAILED"), undeliverable.reason());
            assertEquals(0, fragile.restartCount());
            assertEquals(0, node.stats().escalations());
        }
    }

    @Test
    void shouldRestartFreshWhenThePolicyIsFresh() {
        var counts = new CopyOnWriteArrayList<Long>();
        try (var node = EtherwareNode.builder().nodeId("sup-fresh").build()) {
            Shell fragile = node.add(FRAGILE, () -> new ThirdThrower(counts),
                    SupervisionPolicy.fresh(10, Duration.ofMinutes(1)));
            node.start();
            sendValues(node, FRAGILE, 1, 5);
            awaitProcessed(fragile, 5);
            assertEquals(List.of(1L, 2L, 1L, 2L), counts);
            assertEquals(1, fragile.restartCount());
        }
    }

    @Test
    void shouldStartInRegistrationOrderAndStopInReverseOrder() {
        var events = new CopyOnWriteArrayList<String>();
        try (var node = EtherwareNode.builder().nodeId("sup-order").build()) {
            for (String name : List.of("a", "b", "c")) {
                node.add(Profile.of(name), () -> new Component() {
                    @Override
                    public void onStart(ComponentContext context) {
                        events.add("start " + name);
                    }

                    @Override
                    public void onMessage(Message message, ComponentContext context) {
                    }

                    @Override
                    public void onStop() {
                        events.add("stop " + name);
                    }
                });
            }
            node.start();
        }
        assertEquals(List.of("start a", "start b", "start c", "stop c", "stop b", "stop a"), events);
    }

    @Test
    void shouldMarkTheComponentFailedWhenOnStartThrows() {
        try (var node = EtherwareNode.builder().nodeId("sup-start-fails").build()) {
            Shell broken = node.add(FRAGILE, () -> new Component() {
                @Override
                public void onStart(ComponentContext context) {
                    throw new IllegalStateException("no serial port");
                }

                @Override
                public void onMessage(Message message, ComponentContext context) {
                }
            });
            node.start();
            assertEquals(Shell.State.FAILED, broken.state());
            node.send(FRAGILE, new Text("x"));
            Await.until("the message is undeliverable", () -> node.stats().undeliverable() == 1);
        }
    }
}
