package io.etherware.services.notifier;

import static org.junit.jupiter.api.Assertions.assertEquals;
import static org.junit.jupiter.api.Assertions.assertFalse;
import static org.junit.jupiter.api.Assertions.assertTrue;

import io.etherware.core.codec.MessageCodec;
import io.etherware.core.component.Component;
import io.etherware.core.component.ComponentContext;
import io.etherware.core.kernel.EtherwareNode;
import io.etherware.core.message.Contents;
import io.etherware.core.message.Criticality;
import io.etherware.core.message.Message;
import io.etherware.core.message.MessageId;
import io.etherware.core.message.Profile;
import io.etherware.core.message.QoS;
import io.etherware.core.message.Tick;
import io.etherware.rt.platform.ThreadGrant;
import io.etherware.rt.platform.ThreadPolicy;
import io.etherware.testkit.Await;
import java.util.List;
import java.util.concurrent.CompletableFuture;
import java.util.concurrent.CopyOnWriteArrayList;
import java.util.concurrent.TimeUnit;
import java.util.function.Consumer;
import org.junit.jupiter.api.Test;

/**
 * The Notifier on a real node with real threads and the real clock: subscriptions by message and
 * by Java call, a stalled receiver, runtime changes. Outcomes are asserted with generous margins.
 * The Notifier thread runs at SCHED_OTHER, except where a test needs it on time on a loaded box
 * (the stall tests, the default-priority test): there it has its default SCHED_FIFO 82 and only
 * sleeps, never spins.
 */
class NotifierNodeTest {

    private static final long PERIOD_NS = TimeUnit.MILLISECONDS.toNanos(10);
    private static final long WAIT_MS = 20_000;
    private static final NotifierConfig CONFIG = NotifierConfig.defaults().withThreadPolicy(ThreadPolicy.NON_REALTIME);
    private static final NotifierConfig REALTIME = NotifierConfig.defaults();
    private static final Profile CONTROLLER = Profile.of("controller", "car", "1");

    @Test
    void shouldTickAComponentThatSubscribedByMessageWithTheSubscribedQoS() throws Exception {
        try (var node = EtherwareNode.builder().nodeId("n1").build()) {
            Notifier notifier = Notifier.install(node, CONFIG);
            var receiver = new Receiver();
            var reply = new CompletableFuture<NotifierReply>();
            receiver.onStart = context -> context.request(Notifier.profileFor("n1"),
                            TickSubscribe.periodic(Criticality.HIGH, PERIOD_NS))
                    .thenAccept(message -> reply.complete(message.contentsAs(NotifierReply.class)));
            node.add(CONTROLLER, () -> receiver);
            node.start();

            NotifierReply answer = reply.get(WAIT_MS, TimeUnit.MILLISECONDS);
            assertTrue(answer.accepted(), answer.toString());
            assertEquals(CONTROLLER.toString(), answer.name(), "named after the subscriber");
            long t0Ns = answer.firstReleaseNs();
            Await.until(() -> receiver.ticks.size() + " Ticks", WAIT_MS, () -> receiver.ticks.size() >= 20);

            long previousSequence = -1;
            for (Received received : List.copyOf(receiver.ticks)) {
                Tick tick = received.tick();
                assertEquals(QoS.periodic(Criticality.HIGH, PERIOD_NS), received.message().qos());
                assertEquals(notifier.profile(), received.message().sender());
                assertEquals(t0Ns + tick.sequence() * PERIOD_NS, tick.releaseNs(), "on the grid: " + tick);
                assertEquals(PERIOD_NS, tick.periodNs());
                assertTrue(tick.sequence() > previousSequence, "in order, never repeated: " + tick);
                assertTrue(received.receivedNs() >= tick.releaseNs(), "never before its release: " + tick);
                previousSequence = tick.sequence();
            }
            SubscriptionStats stats = notifier.unsubscribe(CONTROLLER.toString()).orElseThrow();
            assertEquals(stats.ticksSent(), stats.latenessNs().count());
            assertAccountsForEveryRelease(stats);
        }
    }

    @Test
    void shouldSkipAndCountReleasesInsteadOfQueueingABurstWhenTheReceiverStalls() throws Exception {
        try (var node = EtherwareNode.builder().nodeId("n1").build()) {
            Notifier notifier = Notifier.install(node, REALTIME);
            var receiver = new Receiver();
            receiver.stallOnTick = 3;
            receiver.stallMs = 200;
            node.add(CONTROLLER, () -> receiver);
            node.start();
            notifier.subscribe(Subscription.periodic("loop", CONTROLLER, Criticality.HIGH, PERIOD_NS));
            Await.until(() -> receiver.ticks.size() + " Ticks", WAIT_MS, () -> receiver.ticks.size() >= 12);

            long stallEndNs = receiver.stallEndNs;
            List<Received> afterStall = receiver.ticks.subList(4, receiver.ticks.size());
            assertTrue(afterStall.getFirst().tick().releaseNs() > stallEndNs - PERIOD_NS,
                    "no Tick released during the stall waited for the receiver: first after it " + afterStall.getFirst()
                            + ", stall ended at " + stallEndNs);
            SubscriptionStats stats = notifier.unsubscribe("loop").orElseThrow();
            assertTrue(stats.skippedBusy() + stats.skippedLate() >= 10,
                    "the releases during a 200 ms stall at 10 ms are skipped and counted: " + stats);
            assertTrue(stats.skippedBusy() > 0, "skipped for the busy receiver: " + stats);
            Await.until(() -> "every Tick sent to be received: " + receiver.ticks.size() + " of " + stats.ticksSent(),
                    WAIT_MS, () -> receiver.ticks.size() == stats.ticksSent());
            assertAccountsForEveryRelease(stats);
        }
    }

    @Test
    void shouldQueueABurstForAStalledReceiverWhenBackPressureIsOff() throws Exception {
        try (var node = EtherwareNode.builder().nodeId("n1").build()) {
            Notifier notifier = Notifier.install(node, REALTIME);
            var receiver = new Receiver();
            receiver.stallOnTick = 3;
            receiver.stallMs = 200;
            node.add(CONTROLLER, () -> receiver);
            node.start();
            notifier.subscribe(Subscription.periodic("loop", CONTROLLER, Criticality.HIGH, PERIOD_NS)
                    .withBackPressure(false));
            Await.until(() -> receiver.ticks.size() + " Ticks", WAIT_MS, () -> receiver.ticks.size() >= 25);

            long stallEndNs = receiver.stallEndNs;
            long queuedDuringStall = receiver.ticks.stream()
                    .filter(received -> received.tick().releaseNs() < stallEndNs - PERIOD_NS && received.tick().sequence() > 3)
                    .count();
            assertTrue(queuedDuringStall >= 10, "without back-pressure the Ticks queue behind the stall: "
                    + queuedDuringStall);
            assertEquals(0, notifier.stats("loop").orElseThrow().skippedBusy());
        }
    }

    @Test
    void shouldAddRetargetAndRemoveSubscriptionsAtRuntime() throws Exception {
        Profile standby = Profile.of("controller", "car", "2");
        try (var node = EtherwareNode.builder().nodeId("n1").build()) {
            Notifier notifier = Notifier.install(node, CONFIG);
            var first = new Receiver();
            var second = new Receiver();
            node.add(CONTROLLER, () -> first);
            node.add(standby, () -> second);
            node.start();

            Subscription added = notifier.subscribe(
                    Subscription.periodic("loop", CONTROLLER, Criticality.HIGH, PERIOD_NS));
            Await.until(() -> first.ticks.size() + " Ticks at the first", WAIT_MS, () -> first.ticks.size() >= 5);
            notifier.retarget("loop", standby);
            Await.until(() -> second.ticks.size() + " Ticks at the second", WAIT_MS, () -> second.ticks.size() >= 5);
            long lastAtFirst = first.ticks.getLast().tick().sequence();
            Tick firstAtSecond = second.ticks.getFirst().tick();
            assertTrue(firstAtSecond.sequence() > lastAtFirst, "every Tick after the switch goes to the new target,"
                    + " and the sequence continues: last at the first #" + lastAtFirst + ", first at the second "
                    + firstAtSecond);
            assertEquals(added.firstReleaseNs() + firstAtSecond.sequence() * PERIOD_NS, firstAtSecond.releaseNs(),
                    "on the same grid");

            SubscriptionStats last = notifier.unsubscribe("loop").orElseThrow();
            Await.until(() -> "every Tick sent to arrive: " + (first.ticks.size() + second.ticks.size()) + " of "
                            + last.ticksSent(), WAIT_MS,
                    () -> first.ticks.size() + second.ticks.size() == last.ticksSent());
            Thread.sleep(5 * PERIOD_NS / 1_000_000);
            assertEquals(last.ticksSent(), first.ticks.size() + second.ticks.size(), "no Tick after unsubscribe");
            assertEquals(standby, last.subscription().target());
            assertTrue(notifier.stats("loop").isEmpty());
            assertTrue(notifier.unsubscribe("loop").isEmpty());
        }
    }

    @Test
    void shouldRetargetAndUnsubscribeByMessage() throws Exception {
        Profile standby = Profile.of("controller", "car", "2");
        try (var node = EtherwareNode.builder().nodeId("n1").build()) {
            Notifier notifier = Notifier.install(node, CONFIG);
            var first = new Receiver();
            var second = new Receiver();
            node.add(CONTROLLER, () -> first);
            node.add(standby, () -> second);
            node.start();

            assertTrue(ask(node, TickSubscribe.periodic(Criticality.MIDDLE, PERIOD_NS).named("loop").to(CONTROLLER))
                    .accepted());
            Await.until(() -> first.ticks.size() + " Ticks at the first", WAIT_MS, () -> first.ticks.size() >= 3);
            assertTrue(ask(node, new TickRetarget("loop", standby)).accepted());
            Await.until(() -> second.ticks.size() + " Ticks at the second", WAIT_MS, () -> second.ticks.size() >= 3);
            assertEquals(Criticality.MIDDLE, second.ticks.getFirst().message().qos().criticality());
            assertTrue(ask(node, new TickUnsubscribe("loop")).accepted());
            assertTrue(notifier.subscriptions().isEmpty());
        }
    }

    @Test
    void shouldReleaseAOneShotOnceAtTheRequestedTime() throws Exception {
        try (var node = EtherwareNode.builder().nodeId("n1").build()) {
            Notifier notifier = Notifier.install(node, CONFIG);
            var receiver = new Receiver();
            node.add(CONTROLLER, () -> receiver);
            node.start();

            long releaseNs = node.clock().nanoTime() + TimeUnit.MILLISECONDS.toNanos(30);
            NotifierReply reply = ask(node, TickSubscribe.oneShot(Criticality.LOW, releaseNs).named("once")
                    .to(CONTROLLER));
            assertTrue(reply.accepted(), reply.toString());
            assertEquals(releaseNs, reply.firstReleaseNs());
            Await.until(() -> "the one-shot Tick", WAIT_MS, () -> receiver.ticks.size() == 1);
            Thread.sleep(50);

            assertEquals(1, receiver.ticks.size());
            Received received = receiver.ticks.getFirst();
            assertEquals(new Tick(releaseNs, 0, 0), received.tick());
            assertTrue(received.receivedNs() >= releaseNs);
            assertEquals(QoS.of(Criticality.LOW), received.message().qos());
            assertTrue(notifier.stats("once").isEmpty(), "a fired one-shot leaves");
        }
    }

    @Test
    void shouldRefuseBadRequestsNamingTheFieldAndKeepServing() throws Exception {
        try (var node = EtherwareNode.builder().nodeId("n1").build()) {
            Notifier.install(node, CONFIG);
            node.add(CONTROLLER, Receiver::new);
            node.start();

            NotifierReply negative = ask(node, TickSubscribe.periodic(Criticality.HIGH, -5).to(CONTROLLER));
            assertFalse(negative.accepted());
            assertTrue(negative.reason().contains("periodNs=-5"), negative.reason());
            NotifierReply lateness = ask(node, TickSubscribe.periodic(Criticality.HIGH, PERIOD_NS).to(CONTROLLER)
                    .named("y").withMaxLatenessNs(2 * PERIOD_NS));
            assertFalse(lateness.accepted());
            assertTrue(lateness.reason().contains("maxLatenessNs=" + 2 * PERIOD_NS), lateness.reason());
            assertTrue(ask(node, TickSubscribe.periodic(Criticality.HIGH, PERIOD_NS).named("dup").to(CONTROLLER))
                    .accepted());
            NotifierReply duplicate = ask(node, TickSubscribe.periodic(Criticality.LOW, PERIOD_NS).named("dup")
                    .to(CONTROLLER));
            assertFalse(duplicate.accepted());
            assertTrue(duplicate.reason().contains("already in use"), duplicate.reason());
            NotifierReply unknown = ask(node, new TickUnsubscribe("nope"));
            assertFalse(unknown.accepted());
            assertTrue(unknown.reason().contains("nope"), unknown.reason());
            NotifierReply retarget = ask(node, new TickRetarget("nope", CONTROLLER));
            assertFalse(retarget.accepted());
            NotifierReply strange = ask(node, new io.etherware.core.message.Text("tick please"));
            assertFalse(strange.accepted());
            assertTrue(strange.reason().contains("TickSubscribe"), strange.reason());
        }
    }

    @Test
    void shouldRequestSchedFifoOneAboveTableIIByDefaultAndRunOnWhenRefused() {
        var kernel = new RecordingKernel(io.etherware.core.time.NodeClock.system());
        try (var notifier = new Notifier(kernel, NotifierConfig.defaults()).start()) {
            ThreadGrant grant = notifier.threadGrant().orElseThrow();
            assertEquals(ThreadPolicy.fifo(82), grant.requested());
            if (grant.refusals().isEmpty()) {
                assertEquals(ThreadPolicy.fifo(82), grant.granted(), grant.toLine());
            } else {
                assertEquals(ThreadPolicy.NON_REALTIME, grant.granted(), grant.toLine());
                assertEquals("thread priority", grant.refusals().getFirst().feature());
            }
            assertTrue(notifier.isRunning(), "refused or not, it runs");
        }
    }

    @Test
    void shouldRunOnAndTickWhenThePlatformRefusesWhatWasAsked() {
        var kernel = new RecordingKernel(io.etherware.core.time.NodeClock.system());
        kernel.addReceiver(CONTROLLER, true);
        // CPU 1023 does not exist: the affinity request is refused (EINVAL, or ENOSYS off Linux).
        var config = CONFIG.withCpus(io.etherware.rt.platform.CpuSet.of(1023));
        try (var notifier = new Notifier(kernel, config).start()) {
            ThreadGrant grant = notifier.threadGrant().orElseThrow();
            assertEquals("cpu affinity", grant.refusals().getFirst().feature(), grant.toLine());
            notifier.subscribe(Subscription.periodic("loop", CONTROLLER, Criticality.HIGH, PERIOD_NS));
            Await.until(() -> kernel.sentCount() + " Ticks sent", WAIT_MS, () -> kernel.sentCount() >= 3);
        }
    }

    @Test
    void shouldCloseWithTheNode() {
        Notifier notifier;
        try (var node = EtherwareNode.builder().nodeId("n1").build()) {
            notifier = Notifier.install(node, CONFIG);
            node.start();
            assertTrue(notifier.isRunning());
        }
        Await.until(() -> "the Notifier to close with its node", WAIT_MS, () -> !notifier.isRunning());
    }

    @Test
    void shouldCarryItsMessagesThroughTheXmlCodec() {
        var types = new io.etherware.core.message.ContentsTypes();
        Notifier.registerContents(types);
        var codec = new MessageCodec(types);
        for (Contents contents : List.<Contents>of(
                TickSubscribe.periodic(Criticality.HIGH, PERIOD_NS).named("loop").to(CONTROLLER).startingAt(-42L),
                TickSubscribe.oneShot(Criticality.LOW, 123L), new TickUnsubscribe("loop"),
                new TickRetarget("loop", CONTROLLER), NotifierReply.accepted("loop", 7L),
                NotifierReply.refused(null, "periodNs=-5 must be >= 0"))) {
            var message = new Message(Notifier.profileFor("n1"), CONTROLLER, 1L, QoS.NONE, contents,
                    new MessageId("n1", 1), null);
            assertEquals(message, codec.decode(codec.encode(message)), contents.toString());
        }
    }

    // ---------------------------------------------------------------- helpers

    private static NotifierReply ask(EtherwareNode node, Contents request) {
        Message reply = node.requestBlocking(Notifier.profileFor(node.nodeId()), request);
        return reply.contentsAs(NotifierReply.class);
    }

    /** Every release from #0 to the next one is either sent or counted as skipped. */
    private static void assertAccountsForEveryRelease(SubscriptionStats stats) {
        assertEquals(stats.nextSequence(), stats.ticksSent() + stats.skippedReleases(),
                "sent + skipped = releases: " + stats);
    }

    private record Received(Message message, Tick tick, long receivedNs) {
    }

    /** Records the Ticks it gets; optionally stalls in the handler of one of them. */
    private static final class Receiver implements Component {
        final List<Received> ticks = new CopyOnWriteArrayList<>();
        volatile Consumer<ComponentContext> onStart = context -> { };
        volatile long stallOnTick = -1;
        volatile long stallMs;
        volatile long stallEndNs;

        @Override
        public void onStart(ComponentContext context) {
            onStart.accept(context);
        }

        @Override
        public void onMessage(Message message, ComponentContext context) throws InterruptedException {
            if (message.contents() instanceof Tick tick) {
                ticks.add(new Received(message, tick, System.nanoTime()));
                if (ticks.size() == stallOnTick + 1) {
                    Thread.sleep(stallMs); // a stalled receiver: blocks its dispatcher on purpose
                    stallEndNs = System.nanoTime();
                }
            }
        }
    }
}
