package io.etherware.core.kernel;

import static org.junit.jupiter.api.Assertions.assertEquals;
import static org.junit.jupiter.api.Assertions.assertFalse;
import static org.junit.jupiter.api.Assertions.assertInstanceOf;
import static org.junit.jupiter.api.Assertions.assertThrows;
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
import io.etherware.core.testing.MultiDispatcherScheduler;
import io.etherware.core.testing.Num;
import java.time.Duration;
import java.util.ArrayList;
import java.util.List;
import java.util.Set;
import java.util.concurrent.CompletableFuture;
import java.util.concurrent.ConcurrentHashMap;
import java.util.concurrent.CopyOnWriteArrayList;
import java.util.concurrent.CountDownLatch;
import java.util.concurrent.ExecutionException;
import java.util.concurrent.TimeUnit;
import java.util.concurrent.atomic.AtomicBoolean;
import java.util.concurrent.atomic.AtomicLong;
import java.util.function.Supplier;
import java.util.stream.LongStream;
import org.junit.jupiter.api.Test;

/** The hooks of runtime upgrade and migration: hold / release, swap, remove with re-resolution. */
class ManagementHooksTest {

    private static final Profile TARGET = Profile.of("target");
    private static final Profile MARKER = Profile.of("marker");

    /** Counts messages, keeps the values; its count is its state. */
    static class CounterV1 implements Component {
        final List<String> log;
        long count;

        CounterV1(List<String> log) {
            this.log = log;
        }

        @Override
        public void onMessage(Message message, ComponentContext context) {
            count++;
            log.add("v1:" + count);
        }

        @Override
        public ComponentState snapshot() {
            return new Counted(count);
        }

        @Override
        public void restore(ComponentState state) throws Exception {
            count = ((Counted) state).count();
        }
    }

    /** The upgrade: counts in tens from the old count. */
    static final class CounterV2 extends CounterV1 {
        CounterV2(List<String> log) {
            super(log);
        }

        @Override
        public void onMessage(Message message, ComponentContext context) {
            count += 10;
            log.add("v2:" + count);
        }
    }

    @Test
    void shouldKeepMessagesWhileHeldAndDeliverThemInOrderExactlyOnceOnRelease() throws Exception {
        var received = new CopyOnWriteArrayList<Long>();
        var markers = new CopyOnWriteArrayList<String>();
        try (var node = EtherwareNode.builder().nodeId("hold").build()) {
            node.add(TARGET, () -> (message, context) -> received.add(message.contentsAs(Num.class).value()));
            node.add(MARKER, () -> (message, context) -> markers.add("seen"));
            node.start();
            node.send(TARGET, new Num(0));
            Await.until("the first message", () -> received.size() == 1);

            node.hold(TARGET);
            for (long i = 1; i <= 100; i++) {
                node.send(TARGET, new Num(i));
            }
            // The marker is queued after the 100 messages on the one FIFO dispatcher: once it is
            // handled, the target's messages have all been taken and kept.
            node.send(MARKER, new Text("m"));
            Await.until("the marker", () -> markers.size() == 1);
            assertEquals(List.of(0L), received, "nothing is delivered while held");

            node.release(TARGET);
            Await.until("the held messages", () -> received.size() == 101);
            assertEquals(LongStream.rangeClosed(0, 100).boxed().toList(), received);
            node.send(MARKER, new Text("m"));
            Await.until("a second marker", () -> markers.size() == 2);
            assertEquals(101, received.size(), "each held message exactly once");
            assertEquals(101, node.shell(TARGET).handledCount());
        }
    }

    @Test
    void shouldDeliverEveryMessageExactlyOnceWhenHeldSwappedAndReleasedRepeatedlyUnderLoad() throws Exception {
        int senders = 3;
        int perSender = 20_000;
        var seen = ConcurrentHashMap.<Long>newKeySet();
        var duplicates = new AtomicLong();
        var overlaps = new AtomicLong();
        var inside = new AtomicBoolean();
        try (var node = EtherwareNode.builder().nodeId("hold-stress")
                .scheduler(() -> MultiDispatcherScheduler.roundRobin(3)).build()) {
            Supplier<Component> logic = () -> (message, context) -> {
                if (!inside.compareAndSet(false, true)) {
                    overlaps.incrementAndGet();
                }
                if (!seen.add(message.contentsAs(Num.class).value())) {
                    duplicates.incrementAndGet();
                }
                inside.set(false);
            };
            Shell shell = node.add(TARGET, logic);
            node.start();
            var threads = new ArrayList<Thread>();
            for (int s = 0; s < senders; s++) {
                long base = (long) s * perSender;
                threads.add(Thread.ofPlatform().start(() -> {
                    for (long i = 0; i < perSender; i++) {
                        node.send(TARGET, new Num(base + i));
                    }
                }));
            }
            int cycles = 0;
            while (threads.stream().anyMatch(Thread::isAlive) || cycles < 20) {
                node.hold(TARGET);
                if (cycles % 4 == 0) {
                    node.swap(TARGET, logic); // a swap while held: the gate is taken, then left held
                }
                node.release(TARGET);
                cycles++;
            }
            for (Thread thread : threads) {
                thread.join();
            }
            Await.until("every message", () -> shell.handledCount() == (long) senders * perSender);
            assertEquals((long) senders * perSender, seen.size());
            assertEquals(0, duplicates.get());
            assertEquals(0, overlaps.get());
            assertTrue(cycles >= 20);
        }
    }

    @Test
    void shouldReturnFromHoldOnlyOnceTheHandlingInProgressIsOver() throws Exception {
        var entered = new CountDownLatch(1);
        var finish = new CountDownLatch(1);
        var received = new CopyOnWriteArrayList<Long>();
        try (var node = EtherwareNode.builder().nodeId("hold-boundary")
                .scheduler(() -> MultiDispatcherScheduler.roundRobin(2)).build()) {
            node.add(TARGET, () -> (message, context) -> {
                long value = message.contentsAs(Num.class).value();
                if (value == 0) {
                    entered.countDown();
                    assertTrue(finish.await(30, TimeUnit.SECONDS));
                }
                received.add(value);
            });
            node.start();
            node.send(TARGET, new Num(0));
            assertTrue(entered.await(30, TimeUnit.SECONDS));

            CompletableFuture<Void> held = node.holdAsync(TARGET);
            assertFalse(held.isDone(), "the component is inside a handler: not at a boundary yet");
            node.send(TARGET, new Num(1));
            node.send(TARGET, new Num(2));
            finish.countDown();
            held.get(30, TimeUnit.SECONDS);
            assertEquals(List.of(0L), received);
            assertEquals(Shell.State.RUNNING, node.shell(TARGET).state());

            node.release(TARGET);
            Await.until("the kept messages", () -> received.size() == 3);
            assertEquals(List.of(0L, 1L, 2L), received.stream().sorted().toList());
        }
    }

    @Test
    void shouldCarryTheStateIntoTheNewLogicWhenSwapped() {
        var log = new CopyOnWriteArrayList<String>();
        try (var node = EtherwareNode.builder().nodeId("swap").build()) {
            Shell shell = node.add(TARGET, () -> new CounterV1(log));
            node.start();
            for (int i = 0; i < 5; i++) {
                node.send(TARGET, new Num(i));
            }
            Await.until("five messages for v1", () -> shell.handledCount() == 5);
            node.swap(TARGET, () -> new CounterV2(log));
            node.send(TARGET, new Num(5));
            Await.until("the message after the swap", () -> log.size() == 6);
            assertEquals(List.of("v1:1", "v1:2", "v1:3", "v1:4", "v1:5", "v2:15"), log);
            assertEquals(CounterV2.class, shell.logicType());
        }
    }

    @Test
    void shouldKeepTheOldLogicAndReturnTheErrorWhenRestoreThrows() {
        var log = new CopyOnWriteArrayList<String>();
        try (var node = EtherwareNode.builder().nodeId("swap-rollback").build()) {
            Shell shell = node.add(TARGET, () -> new CounterV1(log));
            node.start();
            node.send(TARGET, new Num(1));
            node.send(TARGET, new Num(2));
            Await.until("two messages for v1", () -> shell.handledCount() == 2);
            var error = assertThrows(IllegalStateException.class, () -> node.swap(TARGET, () -> new CounterV1(log) {
                @Override
                public void restore(ComponentState state) throws Exception {
                    throw new Exception("state schema " + state.schemaVersion() + " not supported");
                }
            }));
            assertTrue(error.getMessage().contains("state schema 1 not supported"), error.getMessage());
            assertEquals(CounterV1.class, shell.logicType());
            node.send(TARGET, new Num(3));
            Await.until("the message after the rollback", () -> log.size() == 3);
            assertEquals(List.of("v1:1", "v1:2", "v1:3"), log);
            assertEquals(Shell.State.RUNNING, shell.state());
        }
    }

    @Test
    void shouldForwardTheKeptMessagesInOrderThroughTheRouteWhenRelocated() throws Exception {
        var local = new CopyOnWriteArrayList<Long>();
        var forwarded = new CopyOnWriteArrayList<Long>();
        RemoteRoute route = message -> forwarded.add(message.contentsAs(Num.class).value());
        try (var node = EtherwareNode.builder().nodeId("relocate").build()) {
            node.add(TARGET, () -> new CounterV1(new CopyOnWriteArrayList<>()) {
                @Override
                public void onMessage(Message message, ComponentContext context) {
                    super.onMessage(message, context);
                    local.add(message.contentsAs(Num.class).value());
                }
            });
            node.add(MARKER, () -> (message, context) -> context.reply(message, message.contents()));
            node.start();
            node.send(TARGET, new Num(0));
            Await.until("the first message", () -> local.size() == 1);

            node.hold(TARGET);
            ComponentState state = node.snapshotAsync(TARGET).get(30, TimeUnit.SECONDS);
            assertEquals(new Counted(1), state, "the state a migration ships");
            for (long i = 1; i <= 10; i++) {
                node.send(TARGET, new Num(i));
            }
            node.requestBlocking(MARKER, new Text("m")); // the FIFO queue has passed the 10 messages
            node.relocateAsync(TARGET, route).get(30, TimeUnit.SECONDS);
            node.send(TARGET, new Num(11)); // now straight through the route

            assertEquals(List.of(0L), local);
            assertEquals(LongStream.rangeClosed(1, 11).boxed().toList(), forwarded);
            assertInstanceOf(Endpoint.Remote.class, node.registry().resolve(TARGET));
            assertEquals(0, node.stats().undeliverable());
            assertTrue(node.shells().stream().noneMatch(shell -> shell.profile().equals(TARGET)));
        }
    }

    @Test
    void shouldReinstateARelocatedComponentFromItsStateUnderItsProfile() throws Exception {
        var log = new CopyOnWriteArrayList<String>();
        var forwarded = new CopyOnWriteArrayList<Long>();
        RemoteRoute route = message -> forwarded.add(message.contentsAs(Num.class).value());
        try (var node = EtherwareNode.builder().nodeId("reinstate").build()) {
            Shell notMoved = node.add(MARKER, () -> (message, context) -> { });
            node.add(TARGET, () -> new CounterV1(log));
            node.start();
            node.send(TARGET, new Num(0));
            node.send(TARGET, new Num(1));
            Await.until("two handled", () -> log.size() == 2);
            Shell moved = node.shell(TARGET);
            node.hold(TARGET);
            ComponentState state = node.snapshotAsync(TARGET).get(30, TimeUnit.SECONDS);
            node.relocateAsync(TARGET, route).get(30, TimeUnit.SECONDS);
            node.send(TARGET, new Num(2)); // to the new node, which dies with it
            assertEquals(List.of(2L), forwarded);

            Shell back = node.reinstate(moved, state);
            assertInstanceOf(Endpoint.Local.class, node.registry().resolve(TARGET), "local again");
            assertEquals(Shell.State.RUNNING, back.state());
            node.send(TARGET, new Num(3));
            Await.until("handled here again", () -> log.size() == 3);
            assertEquals(List.of("v1:1", "v1:2", "v1:3"), log, "counting on from the state");
            assertEquals(List.of(2L), forwarded, "nothing more through the route");

            var notRelocated = assertThrows(IllegalArgumentException.class, () -> node.reinstate(notMoved, state));
            assertTrue(notRelocated.getMessage().contains("not a component that node 'reinstate' relocated"),
                    notRelocated.getMessage());
            assertThrows(IllegalArgumentException.class, () -> node.reinstate(back, state), "it was not relocated");
            var twice = assertThrows(IllegalStateException.class, () -> node.reinstate(moved, state));
            assertTrue(twice.getMessage().contains("reinstated already"), twice.getMessage());
        }
    }

    @Test
    void shouldReinstateAStatelessRelocatedComponentWithoutRestoring() throws Exception {
        var handled = new CopyOnWriteArrayList<Long>();
        try (var node = EtherwareNode.builder().nodeId("reinstate-stateless").build()) {
            node.add(TARGET, () -> (message, context) -> handled.add(message.contentsAs(Num.class).value()));
            node.start();
            Shell moved = node.shell(TARGET);
            node.hold(TARGET);
            assertEquals(null, node.snapshotAsync(TARGET).get(30, TimeUnit.SECONDS), "no state to ship");
            node.relocateAsync(TARGET, message -> { }).get(30, TimeUnit.SECONDS);

            node.reinstate(moved, null);
            node.send(TARGET, new Num(7));
            Await.until("handled here again", () -> handled.size() == 1);
            assertEquals(List.of(7L), handled);
        }
    }

    @Test
    void shouldStillDeliverAForwardedMessageThatComesAfterAnAdmissionThatStoppedWaitingForIt() throws Exception {
        var handled = new CopyOnWriteArrayList<Long>();
        Profile arrival = Profile.of("etherware.arrival", "id", "late");
        try (var node = EtherwareNode.builder().nodeId("late-arrival").build()) {
            node.start();
            node.registry().registerRemote(TARGET, message -> { });
            node.addHeld(TARGET, arrival, () -> (message, context) -> handled.add(message.contentsAs(Num.class).value()),
                    ns -> { });
            node.admit(arrival, 2); // the source forwarded two
            node.send(arrival, new Num(1));
            node.admit(arrival, 0); // the hand-over's timer: stop waiting for the second
            Await.until("admitted with one of two", () -> handled.size() == 1);
            assertTrue(node.registry().profiles().contains(arrival), "the second is still awaited there");
            node.send(arrival, new Num(2)); // only late: still delivered
            Await.until("the late one handled", () -> handled.size() == 2);
            assertEquals(List.of(1L, 2L), handled);
            assertFalse(node.registry().profiles().contains(arrival), "both in: the arrival profile is gone");
            assertEquals(0, node.stats().undeliverable());
        }
    }

    @Test
    void shouldHandleTheForwardedMessagesOfAnArrivalBeforeThoseSentToItDirectlyOnceAdmitted() throws Exception {
        var handled = new CopyOnWriteArrayList<Long>();
        var firstNs = new CompletableFuture<Long>();
        var toSource = new CopyOnWriteArrayList<Long>();
        Profile arrival = Profile.of("etherware.arrival", "id", "t1");
        try (var node = EtherwareNode.builder().nodeId("add-held").build()) {
            node.add(MARKER, () -> (message, context) -> context.reply(message, message.contents()));
            node.start();
            // The profile lived elsewhere: a route standing in for the source, displaced by the arrival.
            node.registry().registerRemote(TARGET, message -> toSource.add(message.contentsAs(Num.class).value()));
            var arrived = new CounterV1(new CopyOnWriteArrayList<>()) {
                @Override
                public void onMessage(Message message, ComponentContext context) {
                    super.onMessage(message, context);
                    handled.add(message.contentsAs(Num.class).value() * 1000 + count);
                }
            };
            arrived.restore(new Counted(41));
            long beforeNs = node.clock().nanoTime();
            Shell shell = node.addHeld(TARGET, arrival, () -> arrived, firstNs::complete);
            assertEquals(Shell.State.RUNNING, shell.state(), "started, but held");
            assertEquals(TARGET, shell.profile());
            assertInstanceOf(Endpoint.Local.class, node.registry().resolve(TARGET));
            node.send(TARGET, new Num(9)); // sent here directly: penned behind the forwarded ones
            node.send(arrival, new Num(0)); // forwarded by the source, though it comes later
            node.admit(arrival, 3); // the source forwarded 3: two are still on their way
            node.requestBlocking(MARKER, new Text("m")); // the FIFO queue has passed them
            assertEquals(List.of(), handled, "nothing is handled before the forwarded messages are in");
            assertFalse(firstNs.isDone());

            node.send(arrival, new Num(1));
            node.send(arrival, new Num(2));
            Await.until("the kept messages", () -> handled.size() == 4);
            assertFalse(node.registry().profiles().contains(arrival), "admitted: nothing addresses the arrival now");
            assertEquals(Set.of(MARKER, TARGET), node.registry().profiles());
            node.send(TARGET, new Num(4));
            node.send(TARGET, new Num(5)); // late through the source, which sends to the profile now
            Await.until("six messages", () -> handled.size() == 6);
            assertEquals(List.of(42L, 1043L, 2044L, 9045L, 4046L, 5047L), handled,
                    "forwarded first, then penned, counting on from the state");
            assertEquals(List.of(), toSource);
            assertTrue(firstNs.get(30, TimeUnit.SECONDS) >= beforeNs, "the first handling is reported");
            assertThrows(IllegalArgumentException.class, () -> node.addHeld(TARGET, Profile.of("other"), () -> arrived,
                    ns -> { }), "a profile names one component");
            node.removeAsync(TARGET).get(30, TimeUnit.SECONDS);
            assertEquals(Set.of(MARKER), node.registry().profiles());
        }
    }

    @Test
    void shouldRefuseToHoldOrMoveAnArrivalBeforeItsAdmission() throws Exception {
        var handled = new CopyOnWriteArrayList<Long>();
        Profile arrival = Profile.of("etherware.arrival", "id", "onward");
        try (var node = EtherwareNode.builder().nodeId("arrive-relocate").build()) {
            node.start();
            node.addHeld(TARGET, arrival, () -> (message, context) -> handled.add(message.contentsAs(Num.class).value()),
                    ns -> { });
            node.send(TARGET, new Num(9)); // sent here directly: deferred until the admission
            node.send(arrival, new Num(0)); // forwarded by the source
            // Moved on now, the source's later forwarded messages would follow it behind the 9.
            var refused = assertThrows(IllegalStateException.class, () -> node.relocateAsync(TARGET, message -> { }));
            assertTrue(refused.getMessage().contains("still arriving"), refused.getMessage());
            var held = assertThrows(ExecutionException.class,
                    () -> node.holdAsync(TARGET, Duration.ZERO).get(30, TimeUnit.SECONDS));
            assertInstanceOf(IllegalStateException.class, held.getCause());

            node.admit(arrival, 1);
            Await.until("both handled", () -> handled.size() == 2);
            assertEquals(List.of(0L, 9L), handled, "forwarded first, then the deferred one");
            node.holdAsync(TARGET, Duration.ZERO).get(30, TimeUnit.SECONDS); // admitted: it may move on now
            assertEquals(0, node.stats().undeliverable());
        }
    }

    @Test
    void shouldResolveTheMessagesSentDirectlyAnewWhenAnArrivalIsRemovedBeforeItsAdmission() {
        var handled = new CopyOnWriteArrayList<Long>();
        Profile arrival = Profile.of("etherware.arrival", "id", "gone");
        try (var node = EtherwareNode.builder().nodeId("arrive-remove").build()) {
            node.start();
            node.addHeld(TARGET, arrival, () -> (message, context) -> handled.add(message.contentsAs(Num.class).value()),
                    ns -> { });
            node.send(TARGET, new Num(9)); // deferred
            node.send(arrival, new Num(0)); // kept at the gate
            node.remove(TARGET);
            // Nothing hosts either profile now: both are undeliverable, counted; none vanishes.
            Await.until("two undeliverable", () -> node.stats().undeliverable() == 2);
            assertEquals(List.of(), handled);
        }
    }

    @Test
    void shouldCountTheMessagesSentDirectlyAsDiscardedWhenTheNodeClosesBeforeAnAdmission() {
        Profile arrival = Profile.of("etherware.arrival", "id", "closed");
        var node = EtherwareNode.builder().nodeId("arrive-close").build();
        node.start();
        node.addHeld(TARGET, arrival, () -> (message, context) -> { }, ns -> { });
        node.send(TARGET, new Num(9)); // deferred
        node.send(TARGET, new Num(10));
        node.close();
        assertEquals(2, node.stats().discarded(), "deferred at close: counted, not lost silently");
        assertEquals(0, node.stats().handled());
    }

    @Test
    void shouldForwardTheMessagesStillQueuedForARelocatedComponentBeforeSwitchingItsProfile() throws Exception {
        var forwarded = new CopyOnWriteArrayList<Long>();
        RemoteRoute route = message -> forwarded.add(message.contentsAs(Num.class).value());
        var dispatcherBusy = new CountDownLatch(1);
        var unblock = new CountDownLatch(1);
        Profile blocker = Profile.of("blocker");
        try (var node = EtherwareNode.builder().nodeId("relocate-queued").build()) {
            node.add(TARGET, () -> (message, context) -> { });
            node.add(blocker, () -> (message, context) -> {
                dispatcherBusy.countDown();
                try {
                    unblock.await(30, TimeUnit.SECONDS); // bounded: the test fails rather than hangs
                } catch (InterruptedException e) {
                    Thread.currentThread().interrupt();
                }
            });
            node.start();
            node.send(blocker, new Text("hold the one dispatcher"));
            assertTrue(dispatcherBusy.await(30, TimeUnit.SECONDS));
            node.hold(TARGET);
            for (long i = 1; i <= 5; i++) {
                node.send(TARGET, new Num(i)); // queued at the busy dispatcher, not yet kept
            }
            CompletableFuture<Void> relocated = node.relocateAsync(TARGET, route);
            node.send(TARGET, new Num(6)); // behind the queued ones: the profile is not switched yet
            assertFalse(relocated.isDone(), "the switch waits for the queued messages");
            assertInstanceOf(Endpoint.Local.class, node.registry().resolve(TARGET));
            assertEquals(List.of(), forwarded);

            unblock.countDown();
            relocated.get(30, TimeUnit.SECONDS);
            node.send(TARGET, new Num(7)); // straight through the route now
            assertEquals(LongStream.rangeClosed(1, 7).boxed().toList(), forwarded, "in order, each once");
            assertInstanceOf(Endpoint.Remote.class, node.registry().resolve(TARGET));
        }
    }

    @Test
    void shouldSettleAKeptRequestOutcomeLocallyWhenRelocated() throws Exception {
        var forwarded = new CopyOnWriteArrayList<Message>();
        var replyNow = new CountDownLatch(1);
        var outcome = new CompletableFuture<Message>();
        try (var node = EtherwareNode.builder().nodeId("relocate-outcome").build()) {
            node.add(MARKER, () -> (message, context) -> Thread.ofPlatform().start(() -> {
                try {
                    replyNow.await(30, TimeUnit.SECONDS);
                } catch (InterruptedException e) {
                    return;
                }
                context.reply(message, new Text("answer"));
            }));
            node.add(TARGET, () -> (message, context) -> context.request(MARKER, new Text("question"))
                    .whenComplete((reply, error) -> outcome.complete(reply)));
            node.start();
            node.send(TARGET, new Text("ask"));
            Await.until("the question is asked", () -> node.shell(MARKER).handledCount() == 1);
            node.hold(TARGET);
            replyNow.countDown();
            Await.until("the reply reaches the kernel", () -> node.stats().jobs() == 3);
            assertFalse(outcome.isDone(), "the outcome is kept while the requester is held");

            node.relocateAsync(TARGET, forwarded::add).get(30, TimeUnit.SECONDS);
            assertEquals(new Text("answer"), outcome.get(30, TimeUnit.SECONDS).contents());
            assertEquals(List.of(), forwarded, "a request outcome is not a message for the new host");
        }
    }

    @Test
    void shouldResolveTheKeptMessagesAnewWhenAHeldComponentIsRemoved() {
        var received = new CopyOnWriteArrayList<Long>();
        try (var node = EtherwareNode.builder().nodeId("remove-held").build()) {
            node.add(TARGET, () -> (message, context) -> received.add(message.contentsAs(Num.class).value()));
            node.add(MARKER, () -> (message, context) -> context.reply(message, message.contents()));
            node.start();
            node.hold(TARGET);
            for (long i = 1; i <= 3; i++) {
                node.send(TARGET, new Num(i));
            }
            node.requestBlocking(MARKER, new Text("m"));
            node.remove(TARGET);
            // Nothing hosts the profile any more: each kept message is undeliverable, counted
            // (and its sender told, had it one); none vanishes, none reaches the removed logic.
            Await.until("three undeliverable", () -> node.stats().undeliverable() == 3);
            assertEquals(List.of(), received);
        }
    }

    @Test
    void shouldTellSendersWhenTheRemovedComponentHasNoSuccessor() throws Exception {
        var notices = new CopyOnWriteArrayList<Message>();
        try (var node = EtherwareNode.builder().nodeId("remove").build()) {
            node.add(TARGET, () -> (message, context) -> { });
            node.add(MARKER, () -> new Component() {
                @Override
                public void onMessage(Message message, ComponentContext context) {
                    if (message.contents() instanceof Undeliverable) {
                        notices.add(message);
                    } else {
                        context.send(TARGET, new Num(1));
                    }
                }
            });
            node.start();
            node.remove(TARGET);
            assertEquals(Shell.State.STOPPED, node.shells().stream()
                    .filter(shell -> shell.profile().equals(TARGET)).findAny().map(Shell::state)
                    .orElse(Shell.State.STOPPED));
            node.send(MARKER, new Text("poke"));
            Await.until("the notice", () -> notices.size() == 1);
            var undeliverable = assertInstanceOf(Undeliverable.class, notices.getFirst().contents());
            assertTrue(undeliverable.reason().contains("no component matches profile 'target'"), undeliverable.reason());
            assertThrows(ProfileResolutionException.class, () -> node.shell(TARGET));
        }
    }
}
