package io.etherware.services.management;

import static org.junit.jupiter.api.Assertions.assertEquals;
import static org.junit.jupiter.api.Assertions.assertInstanceOf;
import static org.junit.jupiter.api.Assertions.assertThrows;
import static org.junit.jupiter.api.Assertions.assertTrue;

import example.counter.Counted;
import example.counter.ReportingCounter;
import example.counter.Seq;
import io.etherware.core.kernel.Endpoint;
import io.etherware.core.message.Criticality;
import io.etherware.core.message.Message;
import io.etherware.core.message.MessageId;
import io.etherware.core.message.Origin;
import io.etherware.core.message.Profile;
import io.etherware.core.scheduler.Scheduler;
import io.etherware.rt.platform.ThreadPolicy;
import io.etherware.rt.scheduling.RealtimeScheduler;
import io.etherware.rt.scheduling.RealtimeSchedulerConfig;
import io.etherware.rt.scheduling.ThreadSchedulingRule;
import io.etherware.services.notifier.Notifier;
import io.etherware.services.notifier.NotifierConfig;
import io.etherware.services.notifier.Subscription;
import io.etherware.testkit.Await;
import java.time.Duration;
import java.util.List;
import java.util.Set;
import java.util.concurrent.CompletableFuture;
import java.util.concurrent.CopyOnWriteArrayList;
import java.util.concurrent.CountDownLatch;
import java.util.concurrent.ExecutionException;
import java.util.concurrent.TimeUnit;
import java.util.function.Supplier;
import org.junit.jupiter.api.Test;

/**
 * Migration between two nodes on loopback in one JVM: a stateful counter under a steady stream
 * moves with nothing lost, duplicated or reordered; every failure leaves it running at the source.
 */
class MigrationIT {

    private static final Profile COUNTER = Profile.parse("counter[test=migration]");
    private static final long STREAM_PERIOD_NS = TimeUnit.MICROSECONDS.toNanos(500);
    /** Four ordinary dispatchers (HIGH, MIDDLE, LOW apart): the management steps do not queue behind MIDDLE work. */
    private static final Supplier<Scheduler> FOUR_DISPATCHERS = () -> new RealtimeScheduler(
            RealtimeSchedulerConfig.builder().threadSchedulingRule(ThreadSchedulingRule.nonRealtime(4)).build());

    private static MigrateRequest to(String toNode, Class<?> type) {
        return new MigrateRequest(COUNTER, toNode, type.getName(), null, null);
    }

    private static ManagementFailure failureOf(CompletableFuture<MigrationResult> migration) {
        var error = assertThrows(ExecutionException.class, () -> migration.get(30, TimeUnit.SECONDS));
        return assertInstanceOf(ManagementException.class, error.getCause()).failure();
    }

    private static void assertHostedBy(MigrationNode host, MigrationNode other) {
        assertInstanceOf(Endpoint.Local.class, host.node.registry().resolve(COUNTER), "hosted by " + host.node.nodeId());
        Await.until("'" + other.node.nodeId() + "' routes the counter away",
                () -> other.node.registry().resolve(COUNTER) instanceof Endpoint.Remote);
    }

    @Test
    void shouldMoveAStatefulComponentBackAndForthWithNothingLostUnderAStream() throws Exception {
        try (var a = MigrationNode.start("mig-a", MigrationNode.config().build());
             var b = MigrationNode.start("mig-b", MigrationNode.config().build(), a.address())) {
            a.node.add(COUNTER, ReportingCounter::new);
            a.awaitManagementOf("mig-b");
            b.awaitManagementOf("mig-a");
            var stream = new SeqStream(a.node, COUNTER, STREAM_PERIOD_NS);
            stream.awaitMore(200);

            MigrationResult there = Management.migrate(a.node, "mig-a", COUNTER, "mig-b").get(30, TimeUnit.SECONDS);
            assertEquals("mig-b", there.toNode());
            assertEquals(ReportingCounter.class.getName(), there.implementation());
            assertTrue(there.gapNs() >= 0, "the gap was measured: " + there);
            assertHostedBy(b, a);
            stream.awaitMore(200);

            MigrationResult back = Management.migrate(a.node, "mig-b", COUNTER, "mig-a").get(30, TimeUnit.SECONDS);
            assertEquals("mig-a", back.toNode());
            assertHostedBy(a, b);
            stream.awaitMore(200);

            stream.stopAndAssertExactlyOnceInOrder();
            assertEquals(List.of("mig-a", "mig-b", "mig-a"), stream.handlers(), "handled at A, then B, then A");
            assertEquals(1, a.management.migratedCount());
            assertEquals(1, b.management.migratedCount());
            assertEquals(0, a.node.stats().undeliverable() + b.node.stats().undeliverable());
        }
    }

    /**
     * When the migration relocates the counter, five of its messages wait at its dispatcher
     * behind another component's handling of 3 s, longer than a migration step (1 s here): the
     * relocation's switch waits for them, and the source waits for the switch as long as the
     * target keeps its copy (the hand-over wait, 6 s, less a step), so the counter arrives with the
     * five, in order, nothing lost. The HIGH management requests have a dispatcher of their own.
     */
    @Test
    void shouldWaitForARelocationHeldUpByAnotherComponentsLongHandlingWithNothingLost() throws Exception {
        try (var a = MigrationNode.start("mig-a", FOUR_DISPATCHERS, slowSwitchConfig(6));
             var b = MigrationNode.start("mig-b", FOUR_DISPATCHERS, slowSwitchConfig(6), a.address())) {
            List<Counted> reports = fiveQueuedBehindALongHandling(a, b, 3000);
            MigrationResult moved = Management.migrate(a.node, "mig-a", COUNTER, "mig-b").get(30, TimeUnit.SECONDS);

            assertEquals("mig-b", moved.toNode());
            assertTrue(moved.relocateNs() > TimeUnit.SECONDS.toNanos(1), "the switch took more than a step: "
                    + moved);
            assertHostedBy(b, a);
            Await.until("the five handled at B", () -> reports.size() == 5);
            assertEquals(List.of(new Counted(0, 1), new Counted(1, 2), new Counted(2, 3), new Counted(3, 4),
                    new Counted(4, 5)), reports, "each once, in order");
            assertEquals(0, b.management.abandonedInCount(), "the target kept its copy");
            assertEquals(0, a.node.stats().undeliverable() + b.node.stats().undeliverable());
        }
    }

    /**
     * As above, but the other handling (4 s) outlasts the target's hand-over wait (2.5 s): the
     * target gives its copy up, the late hand-over is answered that nothing of the counter is
     * there, and the counter resumes at the source from the state it handed over. The five
     * messages went to the given-up copy and are lost, counted undeliverable there; the migration
     * fails, saying so.
     */
    @Test
    void shouldResumeAtTheSourceWhenTheTargetGaveItsCopyUpBeforeASlowRelocationSwitched() throws Exception {
        try (var a = MigrationNode.start("mig-a", FOUR_DISPATCHERS, slowSwitchConfig(2.5));
             var b = MigrationNode.start("mig-b", FOUR_DISPATCHERS, slowSwitchConfig(2.5), a.address())) {
            List<Counted> reports = fiveQueuedBehindALongHandling(a, b, 4000);
            var failure = failureOf(Management.migrate(a.node, "mig-a", COUNTER, "mig-b"));

            assertEquals(ManagementFailure.Reason.ROLLED_BACK, failure.reason(), failure.error());
            assertTrue(failure.error().contains("resumed at 'mig-a' from the state it handed over"), failure.error());
            assertEquals(1, b.management.abandonedInCount(), "the target gave its copy up");
            assertHostedBy(a, b);
            a.node.send(COUNTER, new Seq(5), SeqStream.QOS);
            Await.until("handled at A", () -> reports.size() == 1);
            assertEquals(List.of(new Counted(5, 1)), reports, "from the state handed over (none of the five)");
            Await.until("the five counted undeliverable at B", () -> b.node.stats().undeliverable() == 5);
        }
    }

    private static ManagementConfig slowSwitchConfig(double handoverWaitS) {
        return MigrationNode.config().migrationStepTimeout(Duration.ofSeconds(1))
                .handoverWait(Duration.ofMillis((long) (handoverWaitS * 1000))).build();
    }

    /**
     * Adds the sink and the counter to {@code a} and a blocker that handles its one message for
     * {@code blockMs}; once that handling has begun, sends the counter five messages, which queue
     * behind it on the same (MIDDLE) dispatcher. Returns the counter's reports.
     */
    private static List<Counted> fiveQueuedBehindALongHandling(MigrationNode a, MigrationNode b, long blockMs)
            throws InterruptedException {
        Profile blocker = Profile.of("blocker");
        var reports = new CopyOnWriteArrayList<Counted>();
        a.node.add(ReportingCounter.SINK, () -> (message, context) -> reports.add((Counted) message.contents()));
        a.node.add(COUNTER, ReportingCounter::new);
        var blocking = new CountDownLatch(1);
        a.node.add(blocker, () -> (message, context) -> {
            blocking.countDown();
            try {
                Thread.sleep(blockMs);
            } catch (InterruptedException e) {
                Thread.currentThread().interrupt();
            }
        });
        a.awaitManagementOf("mig-b");
        b.awaitManagementOf("mig-a");
        Await.until("B routes the sink", () -> b.node.registry().profiles().contains(ReportingCounter.SINK));
        a.node.send(blocker, new Seq(-1), SeqStream.QOS);
        assertTrue(blocking.await(30, TimeUnit.SECONDS), "the long handling began");
        for (long i = 0; i < 5; i++) {
            a.node.send(COUNTER, new Seq(i), SeqStream.QOS);
        }
        return reports;
    }

    @Test
    void shouldLeaveNothingBehindAfterManyMovesAndFollowTheComponentOnToAThirdNode() throws Exception {
        try (var a = MigrationNode.start("mig-a", MigrationNode.config().build());
             var b = MigrationNode.start("mig-b", MigrationNode.config().build(), a.address());
             var c = MigrationNode.start("mig-c", MigrationNode.config().build(), a.address(), b.address())) {
            a.node.add(COUNTER, ReportingCounter::new);
            for (MigrationNode node : List.of(a, b, c)) {
                for (String other : List.of("mig-a", "mig-b", "mig-c")) {
                    if (!other.equals(node.node.nodeId())) {
                        node.awaitManagementOf(other);
                    }
                }
            }
            var stream = new SeqStream(a.node, COUNTER, STREAM_PERIOD_NS);
            Await.until("every node routes the counter and the sink", () -> List.of(b, c).stream().allMatch(node ->
                    node.node.registry().profiles().containsAll(Set.of(COUNTER, ReportingCounter.SINK))));
            stream.awaitMore(100);
            Set<Profile> atA = a.node.registry().profiles();
            Set<Profile> atB = b.node.registry().profiles();

            int roundTrips = 10;
            for (int i = 0; i < roundTrips; i++) {
                Management.migrate(a.node, "mig-a", COUNTER, "mig-b").get(30, TimeUnit.SECONDS);
                stream.awaitMore(40);
                Management.migrate(a.node, "mig-b", COUNTER, "mig-a").get(30, TimeUnit.SECONDS);
                assertHostedBy(a, b);
                stream.awaitMore(40);
            }
            stream.stopAndAssertExactlyOnceInOrder();
            assertEquals(2 * roundTrips + 1, stream.handlers().size(), "A, then B and A in turn: " + stream.handlers());
            // Nothing accumulates: no arrival profile, no route left behind, no shell kept.
            Await.until("B routes the counter to A again", () -> b.node.registry().profiles().equals(atB));
            assertEquals(atA, a.node.registry().profiles());
            for (MigrationNode node : List.of(a, b, c)) {
                assertTrue(node.node.registry().profiles().stream().noneMatch(p -> p.role().equals("etherware.arrival")),
                        node.node.nodeId() + " keeps no arrival profile: " + node.node.registry().profiles());
            }
            assertEquals(1, a.node.shells().stream().filter(shell -> shell.profile().equals(COUNTER)).count());
            assertTrue(b.node.shells().stream().noneMatch(shell -> shell.profile().equals(COUNTER)));

            // A to B, then B on to C: A follows the component to C and no longer needs B.
            Management.migrate(a.node, "mig-a", COUNTER, "mig-b").get(30, TimeUnit.SECONDS);
            Management.migrate(a.node, "mig-b", COUNTER, "mig-c").get(30, TimeUnit.SECONDS);
            Await.until("A routes the counter to C, not through B", () ->
                    a.node.registry().resolve(COUNTER) instanceof Endpoint.Remote remote
                            && remote.route().isServedBy("mig-c") && !remote.route().isServedBy("mig-b"));
            b.close();
            long sent = stream.sent();
            for (long i = sent; i < sent + 20; i++) {
                a.node.send(COUNTER, new example.counter.Seq(i), SeqStream.QOS);
            }
            Await.until("20 more reports", () -> stream.reports.size() == sent + 20);
            List<example.counter.Counted> handled = stream.handled();
            assertEquals(sent + 20, handled.getLast().count(), "the count went on at C: " + handled.getLast());
            assertEquals("mig-c", stream.handlers().getLast());
        }
    }

    /** Starts a migration of the counter from A to B under the stream; the counter must stay at A. */
    private static void assertResumesAtSource(MigrationNode a, MigrationNode b, MigrateRequest request,
                                              ManagementFailure.Reason reason, String errorPart) throws Exception {
        a.node.add(COUNTER, ReportingCounter::new);
        a.awaitManagementOf(b.node.nodeId());
        var stream = new SeqStream(a.node, COUNTER, STREAM_PERIOD_NS);
        stream.awaitMore(100);

        ManagementFailure failure = failureOf(Management.migrate(a.node, "mig-a", request, Duration.ofSeconds(30)));
        assertEquals(reason, failure.reason(), failure.error());
        assertTrue(failure.error().contains(errorPart), failure.error());
        stream.awaitMore(100);

        stream.stopAndAssertExactlyOnceInOrder();
        assertEquals(List.of("mig-a"), stream.handlers(), "every message handled at the source");
        assertInstanceOf(Endpoint.Local.class, a.node.registry().resolve(COUNTER));
        assertEquals(0, a.management.migratedCount());
    }

    @Test
    void shouldResumeAtTheSourceWhenTheClassIsMissingOnTheTarget() throws Exception {
        try (var a = MigrationNode.start("mig-a", MigrationNode.config().build());
             var b = MigrationNode.start("mig-b", MigrationNode.config().build(), a.address())) {
            var request = new MigrateRequest(COUNTER, "mig-b", "example.counter.NoSuchCounter", null, null);
            assertResumesAtSource(a, b, request, ManagementFailure.Reason.CLASS_NOT_LOADABLE,
                    "'example.counter.NoSuchCounter' not found on the class path");
        }
    }

    @Test
    void shouldResumeAtTheSourceWhenRestoreThrowsOnTheTarget() throws Exception {
        try (var a = MigrationNode.start("mig-a", MigrationNode.config().build());
             var b = MigrationNode.start("mig-b", MigrationNode.config().build(), a.address())) {
            assertResumesAtSource(a, b, to("mig-b", ReportingCounter.FailingRestore.class),
                    ManagementFailure.Reason.ROLLED_BACK, "refuses every state");
            assertThrows(RuntimeException.class, () -> b.node.shell(COUNTER), "nothing stays registered at B");
        }
    }

    @Test
    void shouldResumeAtTheSourceWhenTheTargetIsUnreachable() throws Exception {
        try (var a = MigrationNode.start("mig-a", MigrationNode.config().build());
             var b = MigrationNode.start("mig-b", MigrationNode.config().build(), a.address())) {
            assertResumesAtSource(a, b, MigrateRequest.of(COUNTER, "nowhere"), ManagementFailure.Reason.TARGET_UNREACHABLE,
                    "node 'nowhere' did not answer the PREPARE step");
        }
    }

    @Test
    void shouldResumeAtTheSourceAndTheTargetShouldGiveUpItsCopyWhenTheTargetAnswersTooLate() throws Exception {
        ManagementConfig quick = MigrationNode.config().migrationStepTimeout(Duration.ofMillis(300))
                .handoverWait(Duration.ofMillis(600)).build();
        try (var a = MigrationNode.start("mig-a", quick);
             var b = MigrationNode.start("mig-b", quick, a.address())) {
            assertResumesAtSource(a, b, to("mig-b", ReportingCounter.SlowRestore.class),
                    ManagementFailure.Reason.TARGET_UNREACHABLE, "did not answer the INSTALL step");
            // B registers its copy once the slow restore is over, then gives it up: never handed over.
            Await.until("B gives its copy up", () -> !b.node.registry().profiles().contains(COUNTER)
                    || b.node.registry().resolve(COUNTER) instanceof Endpoint.Remote);
            Thread.sleep(ReportingCounter.SlowRestore.RESTORE_MS + 1_000); // past the restore and the hand-over wait
            assertTrue(b.node.shells().stream().noneMatch(shell -> shell.profile().equals(COUNTER)),
                    "B's copy was removed");
            assertInstanceOf(Endpoint.Local.class, a.node.registry().resolve(COUNTER), "A still hosts it");
        }
    }

    @Test
    void shouldKeepDeliveringTheTicksOfTheSourcesNotifierAfterTheComponentMoves() throws Exception {
        Profile ticker = Profile.parse("ticker[test=migration]");
        try (var a = MigrationNode.start("mig-a", MigrationNode.config().build());
             var b = MigrationNode.start("mig-b", MigrationNode.config().build(), a.address())) {
            var reports = new CopyOnWriteArrayList<Message>();
            a.node.add(ReportingCounter.SINK, () -> (message, context) -> reports.add(message));
            a.node.add(ticker, ReportingCounter.TickReporter::new);
            Notifier notifier = Notifier.install(a.node,
                    NotifierConfig.defaults().withThreadPolicy(ThreadPolicy.NON_REALTIME));
            notifier.subscribe(Subscription.periodic("ticker", ticker, Criticality.MIDDLE,
                    TimeUnit.MILLISECONDS.toNanos(2)));
            a.awaitManagementOf("mig-b");
            Await.until("ticks at A", () -> reports.size() >= 20);

            Management.migrate(a.node, "mig-a", ticker, "mig-b").get(30, TimeUnit.SECONDS);
            Await.until("ticks at B", () -> reports.stream().filter(r -> r.messageId().nodeId().equals("mig-b"))
                    .count() >= 20);

            var handled = reports.stream().map(r -> (Counted) r.contents())
                    .sorted(java.util.Comparator.comparingLong(Counted::count)).toList();
            for (int i = 0; i < handled.size(); i++) {
                assertEquals(i + 1, handled.get(i).count(), "the count continues at B: " + handled);
                if (i > 0) {
                    assertTrue(handled.get(i).sequence() > handled.get(i - 1).sequence(),
                            "each Tick once, in order: " + handled);
                }
            }
            assertEquals(0, notifier.stats("ticker").orElseThrow().skippedUndeliverable(), "the profile always resolved");
        }
    }

    @Test
    void shouldRefuseAMigrationRequestedFromAnotherNodeByDefault() throws Exception {
        try (var a = MigrationNode.start("mig-a", ManagementConfig.defaults())) {
            a.node.add(COUNTER, ReportingCounter::new);
            var inbox = new CopyOnWriteArrayList<Message>();
            Profile inboxProfile = Profile.of("inbox");
            a.node.add(inboxProfile, () -> (message, context) -> inbox.add(message));
            // The id names the node itself, as in the attack; the origin says where it came from.
            a.node.send(new Message(Management.profileOf("mig-a"), inboxProfile, a.node.clock().epochNanos(),
                    Management.REQUEST_QOS, MigrateRequest.of(COUNTER, "mig-b"), new MessageId("mig-a", 3_000), null)
                    .withOrigin(Origin.direct("elsewhere", true)));
            Await.until("the answer", () -> inbox.size() == 1);
            var failure = assertInstanceOf(ManagementFailure.class, inbox.getFirst().contents());
            assertEquals(ManagementFailure.Reason.REMOTE_REFUSED, failure.reason());
            assertEquals("migrate", failure.operation());
            assertTrue(failure.error().contains("node 'elsewhere' may not migrate '" + COUNTER + "'"), failure.error());
            assertTrue(failure.error().contains("allowRemote(\"elsewhere\", Set.of(Operation.MIGRATE)"), failure.error());
            assertInstanceOf(Endpoint.Local.class, a.node.registry().resolve(COUNTER), "nothing moved");
            assertEquals(1, a.management.refusedCount());
        }
    }

    @Test
    void shouldResumeAtTheSourceWhenTheTargetsAccessListDoesNotLetTheSourceMigrateIt() throws Exception {
        ManagementConfig onlyOthers = ManagementConfig.builder().allowUnauthenticatedLinks(true)
                .allowRemote("mig-c", Set.of(AccessRule.Operation.MIGRATE), "*")
                .allowRemote("mig-a", Set.of(AccessRule.Operation.UPGRADE, AccessRule.Operation.MIGRATE), "other*")
                .build();
        try (var a = MigrationNode.start("mig-a", MigrationNode.config().build());
             var b = MigrationNode.start("mig-b", onlyOthers, a.address())) {
            assertResumesAtSource(a, b, MigrateRequest.of(COUNTER, "mig-b"), ManagementFailure.Reason.REMOTE_REFUSED,
                    "node 'mig-a' may not migrate '" + COUNTER + "' on node 'mig-b' (migration PREPARE)");
            assertEquals(1, b.management.refusedCount());
            assertTrue(b.node.shells().stream().noneMatch(shell -> shell.profile().equals(COUNTER)), "nothing at B");
        }
    }

    @Test
    void shouldRefuseAStepThatNamesAnotherSourceThanTheNodeItCameFrom() throws Exception {
        try (var b = MigrationNode.start("mig-b", MigrationNode.config().build())) {
            var inbox = new CopyOnWriteArrayList<Message>();
            Profile inboxProfile = Profile.of("inbox");
            b.node.add(inboxProfile, () -> (message, context) -> inbox.add(message));
            var step = new MigrationStep(MigrationStep.Phase.PREPARE, COUNTER, "mig-a",
                    Profile.of("etherware.arrival", "id", "forged"), ReportingCounter.class.getName(), null, null, null, 0, 0);
            b.node.send(new Message(Management.profileOf("mig-b"), inboxProfile, b.node.clock().epochNanos(),
                    Management.REQUEST_QOS, step, new MessageId("mig-a", 1), null)
                    .withOrigin(Origin.direct("mig-c", true)));
            Await.until("the answer", () -> inbox.size() == 1);
            var failure = assertInstanceOf(ManagementFailure.class, inbox.getFirst().contents());
            assertEquals(ManagementFailure.Reason.REMOTE_REFUSED, failure.reason());
            assertTrue(failure.error().contains("says it comes from node 'mig-a' but arrived from node 'mig-c'"),
                    failure.error());
            assertEquals(1, b.management.refusedCount());
        }
    }

    /**
     * A stand-in target's management service on the source node answers the PREPARE step as if it
     * came from {@code answeredFrom}; returns the steps it saw and the migration's failure.
     */
    private static List<MigrationStep.Phase> stepsSeenWhenAnsweredFrom(String answeredFrom,
            ManagementFailure.Reason reason, String errorPart) throws Exception {
        ManagementConfig quick = MigrationNode.config().migrationStepTimeout(Duration.ofMillis(300))
                .handoverWait(Duration.ofMillis(600)).build();
        try (var a = MigrationNode.start("mig-a", quick)) {
            a.node.add(COUNTER, ReportingCounter::new);
            var steps = new CopyOnWriteArrayList<MigrationStep.Phase>();
            a.node.add(Management.profileOf("fake-target"), () -> (message, context) -> {
                var step = (MigrationStep) message.contents();
                steps.add(step.phase());
                if (step.phase() == MigrationStep.Phase.PREPARE) {
                    // The stand-in is local, so an answer "from the target" is local code's (no
                    // origin); one from another node carries that node's origin.
                    Message answer = new Message(message.sender(), context.self(), a.node.clock().epochNanos(),
                            Management.REQUEST_QOS, new MigrationStepDone(step.phase(), step.target(),
                            ReportingCounter.class.getName(), 0, -1), new MessageId(answeredFrom, steps.size()),
                            message.messageId());
                    a.node.send(answeredFrom.equals("fake-target") ? answer
                            : answer.withOrigin(Origin.direct(answeredFrom, true)));
                }
            });
            ManagementFailure failure = failureOf(Management.migrate(a.node, "mig-a", COUNTER, "fake-target",
                    Duration.ofSeconds(30)));
            assertEquals(reason, failure.reason(), failure.error());
            assertTrue(failure.error().contains(errorPart), failure.error());
            assertInstanceOf(Endpoint.Local.class, a.node.registry().resolve(COUNTER), "the counter stayed at A");
            return List.copyOf(steps);
        }
    }

    @Test
    void shouldTakeAStepsAnswerOnlyFromTheTargetNode() throws Exception {
        // From the target: taken, so the migration goes on to INSTALL (unanswered here, so it fails).
        assertEquals(List.of(MigrationStep.Phase.PREPARE, MigrationStep.Phase.INSTALL),
                stepsSeenWhenAnsweredFrom("fake-target", ManagementFailure.Reason.TARGET_UNREACHABLE,
                        "did not answer the INSTALL step"));
        // From a third node that learned the step's id: the kernel drops it (the request's profile
        // is not served by that node), so the step goes unanswered and the migration stops there.
        assertEquals(List.of(MigrationStep.Phase.PREPARE),
                stepsSeenWhenAnsweredFrom("intruder", ManagementFailure.Reason.TARGET_UNREACHABLE,
                        "did not answer the PREPARE step"));
    }
}
