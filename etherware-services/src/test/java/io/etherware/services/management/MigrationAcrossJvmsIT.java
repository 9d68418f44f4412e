package io.etherware.services.management;

import static org.junit.jupiter.api.Assertions.assertEquals;
import static org.junit.jupiter.api.Assertions.assertInstanceOf;
import static org.junit.jupiter.api.Assertions.assertThrows;
import static org.junit.jupiter.api.Assertions.assertTrue;

import example.counter.Counted;
import example.counter.ReportingCounter;
import example.counter.Seq;
import io.etherware.core.component.RequestFailedException;
import io.etherware.core.component.Shell;
import io.etherware.core.kernel.Endpoint;
import io.etherware.core.kernel.ProfileResolutionException;
import io.etherware.core.message.Profile;
import io.etherware.testkit.Await;
import java.io.BufferedReader;
import java.io.IOException;
import java.io.InputStreamReader;
import java.nio.charset.StandardCharsets;
import java.nio.file.Files;
import java.nio.file.Path;
import java.time.Duration;
import java.util.List;
import java.util.Optional;
import java.util.concurrent.CompletableFuture;
import java.util.concurrent.CopyOnWriteArrayList;
import java.util.concurrent.ExecutionException;
import java.util.concurrent.TimeUnit;
import org.junit.jupiter.api.Test;
import org.junit.jupiter.api.io.TempDir;
import org.junit.jupiter.params.ParameterizedTest;
import org.junit.jupiter.params.provider.CsvSource;

/**
 * Migration between two JVMs on loopback: the second JVM ({@link MigrationPeer}) runs on the same
 * class path. A stateful counter under a steady stream of sequence-numbered messages moves there
 * and back with nothing lost, duplicated or reordered; when the target JVM is killed inside the
 * PREPARE or the INSTALL step of a migration, the counter resumes at the source with nothing lost,
 * and when it is killed after the relocation, from the state it was handed;
 * when the source JVM is killed inside the PREPARE step or the snapshot, the target gives the
 * migration up and keeps nothing of it; when it is killed after sending the INSTALL, the target runs
 * the counter from the state handed over.
 */
class MigrationAcrossJvmsIT {

    private static final Profile COUNTER = Profile.parse("counter[test=jvm-migration]");
    private static final long STREAM_PERIOD_NS = TimeUnit.MICROSECONDS.toNanos(500);
    private static final Duration STEP_TIMEOUT = Duration.ofSeconds(2);

    @TempDir
    Path logs;

    /** The other JVM, connected to {@code a} once this returns. */
    private Process startPeer(MigrationNode a, String nodeId) throws IOException, InterruptedException {
        return startPeer(a, nodeId, Duration.ofSeconds(1));
    }

    /** @param firstMessageWait how long the peer answers a hand-over late when no message comes */
    private Process startPeer(MigrationNode a, String nodeId, Duration firstMessageWait)
            throws IOException, InterruptedException {
        String classPath = System.getProperty("surefire.test.class.path", System.getProperty("java.class.path"));
        var command = List.of(Path.of(System.getProperty("java.home"), "bin", "java").toString(),
                "--enable-native-access=ALL-UNNAMED", "-cp", classPath, MigrationPeer.class.getName(), nodeId,
                "127.0.0.1", String.valueOf(a.address().getPort()), String.valueOf(STEP_TIMEOUT.toMillis()),
                a.node.nodeId(), String.valueOf(firstMessageWait.toMillis()));
        Path err = logs.resolve(nodeId + ".err");
        Process process = new ProcessBuilder(command).redirectError(err.toFile()).start();
        var ready = CompletableFuture.supplyAsync(() -> {
            try (var out = new BufferedReader(new InputStreamReader(process.getInputStream(), StandardCharsets.UTF_8))) {
                return "READY".equals(out.readLine());
            } catch (IOException e) {
                return false;
            }
        });
        try {
            if (!ready.get(60, TimeUnit.SECONDS)) {
                throw new AssertionError("the peer JVM did not start: " + Files.readString(err));
            }
        } catch (ExecutionException | java.util.concurrent.TimeoutException e) {
            process.destroyForcibly();
            throw new AssertionError("the peer JVM did not start: " + Files.readString(err), e);
        }
        a.awaitManagementOf(nodeId);
        return process;
    }

    /** This JVM's node, with the counter; it accepts the steps of a migration back from the peer. */
    private static MigrationNode sourceWithCounter() {
        var a = MigrationNode.start("jvm-a", MigrationNode.config().migrationStepTimeout(STEP_TIMEOUT)
                .handoverWait(STEP_TIMEOUT.multipliedBy(2)).build());
        a.node.add(COUNTER, ReportingCounter::new);
        return a;
    }

    private static void stop(Process process) throws InterruptedException {
        try {
            process.getOutputStream().close();
        } catch (IOException e) {
            // already gone
        }
        if (!process.waitFor(30, TimeUnit.SECONDS)) {
            process.destroyForcibly();
        }
    }

    @Test
    void shouldMoveAStatefulComponentToAnotherJvmAndBackWithNothingLostUnderAStream() throws Exception {
        try (var a = sourceWithCounter()) {
            Process b = startPeer(a, "jvm-b");
            try {
                var stream = new SeqStream(a.node, COUNTER, STREAM_PERIOD_NS);
                stream.awaitMore(200);

                MigrationResult there = Management.migrate(a.node, "jvm-a", COUNTER, "jvm-b")
                        .get(60, TimeUnit.SECONDS);
                assertEquals("jvm-b", there.toNode());
                assertTrue(there.gapNs() >= 0, "the gap was measured: " + there);
                assertInstanceOf(Endpoint.Remote.class, a.node.registry().resolve(COUNTER), "A routes it to B");
                stream.awaitMore(200);
                Await.until("B handles the stream", () -> stream.handlers().getLast().equals("jvm-b"));

                MigrationResult back = Management.migrate(a.node, "jvm-b", COUNTER, "jvm-a")
                        .get(60, TimeUnit.SECONDS);
                assertEquals("jvm-a", back.toNode());
                assertInstanceOf(Endpoint.Local.class, a.node.registry().resolve(COUNTER), "A hosts it again");
                stream.awaitMore(200);

                stream.stopAndAssertExactlyOnceInOrder();
                assertEquals(List.of("jvm-a", "jvm-b", "jvm-a"), stream.handlers(), "handled at A, then B, then A");
                assertEquals(0, a.node.stats().undeliverable());
            } finally {
                stop(b);
            }
            Await.until("B's connections closed", () -> a.net.peer("jvm-b").map(peer -> !peer.connected()).orElse(true));
            assertEquals(Optional.empty(), a.net.goneWithoutGoodbye("jvm-b"), "B closed its messenger: it said goodbye");
        }
    }

    /**
     * The target JVM is killed (SIGKILL) inside a step: in PREPARE (the class constructs for 1.5 s,
     * the counter still runs at the source) or in INSTALL (the state restores for 1.5 s, the source
     * holds the counter). Either way the counter resumes at the source, every message of the
     * stream handled there exactly once and in order.
     */
    @ParameterizedTest(name = "killed in {0}")
    @CsvSource({
        "PREPARE, example.counter.ReportingCounter$SlowConstruct, did not answer the PREPARE step",
        "INSTALL, example.counter.ReportingCounter$SlowRestore, resumed at 'jvm-a'"})
    void shouldResumeAtTheSourceWithNothingLostWhenTheTargetJvmIsKilledDuringAStep(String step, String className,
            String expectedError) throws Exception {
        try (var a = sourceWithCounter()) {
            Process b = startPeer(a, "jvm-b");
            try {
                var stream = new SeqStream(a.node, COUNTER, STREAM_PERIOD_NS);
                stream.awaitMore(200);
                var request = new MigrateRequest(COUNTER, "jvm-b", className, null, null);
                CompletableFuture<MigrationResult> migration = Management.migrate(a.node, "jvm-a", request,
                        Duration.ofSeconds(60));
                Thread.sleep(500); // inside the 1.5 s step
                b.destroyForcibly();
                assertTrue(b.waitFor(30, TimeUnit.SECONDS), "the target JVM is gone");

                var error = assertThrows(ExecutionException.class, () -> migration.get(60, TimeUnit.SECONDS));
                var failure = assertInstanceOf(ManagementException.class, error.getCause()).failure();
                assertEquals(ManagementFailure.Reason.TARGET_UNREACHABLE, failure.reason(), step + ": " + failure.error());
                assertTrue(failure.error().contains(expectedError), step + ": " + failure.error());
                stream.awaitMore(200);

                stream.stopAndAssertExactlyOnceInOrder();
                assertEquals(List.of("jvm-a"), stream.handlers(), "every message handled at the source");
                assertInstanceOf(Endpoint.Local.class, a.node.registry().resolve(COUNTER));
            } finally {
                b.destroyForcibly();
            }
        }
    }

    /**
     * The target JVM is killed (SIGKILL) after the relocation, while this node waits for the
     * answer to the hand-over (the counter, sent nothing, is answered for only after the target's
     * first-message wait of 5 s): the target had the counter's state but ran nothing of it, so the
     * counter resumes here from that state, under its profile, counting on; the migration fails
     * saying so.
     */
    @Test
    void shouldResumeAtTheSourceFromTheStateHandedOverWhenTheTargetJvmIsKilledAfterTheRelocation()
            throws Exception {
        try (var a = sourceWithCounter()) {
            List<Counted> reports = sinkAt(a);
            for (long i = 0; i < 5; i++) {
                a.node.send(COUNTER, new Seq(i), SeqStream.QOS);
            }
            Await.until("five handled here", () -> reports.size() == 5);
            Shell before = a.node.shell(COUNTER);
            // It answers the hand-over of an idle component after 5 s: time to kill it in between.
            Process b = startPeer(a, "jvm-b", Duration.ofSeconds(5));
            try {
                var move = Management.migrate(a.node, "jvm-a", COUNTER, "jvm-b", Duration.ofSeconds(30));
                Await.until("relocated to B", () -> move.isDone()
                        || resolveOrNull(a, COUNTER) instanceof Endpoint.Remote);
                assertTrue(!move.isDone(), "the hand-over was not answered yet: " + move);
                b.destroyForcibly();
                assertTrue(b.waitFor(30, TimeUnit.SECONDS), "the target JVM is gone");

                var error = assertThrows(ExecutionException.class, () -> move.get(60, TimeUnit.SECONDS));
                var failure = assertInstanceOf(ManagementException.class, error.getCause()).failure();
                assertEquals(ManagementFailure.Reason.TARGET_UNREACHABLE, failure.reason(), failure.error());
                assertTrue(failure.error().contains("resumed at 'jvm-a' from the state it handed over"),
                        failure.error());
                assertInstanceOf(Endpoint.Local.class, a.node.registry().resolve(COUNTER), "it runs here again");
                Shell after = a.node.shell(COUNTER);
                assertTrue(after != before, "a new instance, from the state handed over");
                assertEquals(Shell.State.RUNNING, after.state());
                a.node.send(COUNTER, new Seq(5), SeqStream.QOS);
                Await.until("the next one handled here", () -> reports.size() == 6);
                assertEquals(new Counted(5, 6), reports.getLast(), "counting on from the state handed over");
                assertEquals(List.of(), arrivalProfiles(a));
            } finally {
                b.destroyForcibly();
            }
        }
    }

    /**
     * The source JVM is killed (SIGKILL) inside a step of a migration to this JVM before its state
     * left: while this node constructs the new instance (PREPARE), or while the source takes the
     * state (the snapshot). The component dies with its node, as it would without a migration;
     * this node gives the migration up after its waits, counts it as abandoned, and keeps nothing
     * of it: no prepared instance, no arrival profile.
     */
    @ParameterizedTest(name = "source killed in {0}")
    @CsvSource(nullValues = "none", value = {
        "PREPARE, none, example.counter.ReportingCounter$SlowConstruct",
        "SNAPSHOT, example.counter.ReportingCounter$SlowSnapshot, none"})
    void shouldKeepNothingOfTheMigrationWhenTheSourceJvmIsKilledDuringAStep(String step, String classAtSource,
            String classHere) throws Exception {
        try (var a = sourceWithCounter()) {
            Process b = startPeer(a, "jvm-b");
            try {
                Management.migrate(a.node, "jvm-a", new MigrateRequest(COUNTER, "jvm-b", classAtSource, null, null),
                        Duration.ofSeconds(60)).get(60, TimeUnit.SECONDS);
                assertInstanceOf(Endpoint.Remote.class, a.node.registry().resolve(COUNTER), "B hosts the counter");

                // B moves it back here, and dies in the middle.
                var back = Management.migrate(a.node, "jvm-b", new MigrateRequest(COUNTER, "jvm-a", classHere, null,
                        null), Duration.ofSeconds(5));
                Thread.sleep(500); // inside the 1.5 s step
                b.destroyForcibly();
                assertTrue(b.waitFor(30, TimeUnit.SECONDS), "the source JVM is gone");

                Await.until(() -> step + ": abandoned " + a.management.abandonedInCount() + ", arrival profiles "
                        + arrivalProfiles(a), 30_000, () -> a.management.abandonedInCount() == 1);
                assertEquals(List.of(), arrivalProfiles(a), "no arrival profile stays");
                assertEquals(0, a.management.migratedInCount(), "nothing was handed over here");
                assertTrue(!(resolveOrNull(a, COUNTER) instanceof Endpoint.Local), step + ": this node does not run"
                        + " the counter");
                var error = assertThrows(ExecutionException.class, () -> back.get(60, TimeUnit.SECONDS));
                assertInstanceOf(RequestFailedException.class, error.getCause(), "the request to the dead node"
                        + " fails when it times out");
            } finally {
                b.destroyForcibly();
            }
        }
    }

    /**
     * The source JVM is killed (SIGKILL) after it sent the INSTALL of a migration to this JVM:
     * while this node restores the state (the restore takes 1.5 s, so the INSTALL is not even
     * answered), or as soon as the state is installed here, while the source relocates and hands
     * over (a race: the hand-over usually arrives first). The source holds the component, or has
     * forwarded it, since it sent the INSTALL, and being dead it never resumes it; so this node runs
     * it, with the state handed over: it takes it over once the source has left without a goodbye and
     * stayed away for a step's time, or admits it if the hand-over came. Exactly one instance runs,
     * here, and counts on from that state; nothing of the migration stays registered.
     */
    @ParameterizedTest(name = "source killed {0}")
    @CsvSource({"in INSTALL, true", "after INSTALL, false"})
    void shouldRunTheComponentHereWhenTheSourceJvmIsKilledAfterSendingTheInstall(String when, boolean slowRestore)
            throws Exception {
        try (var a = sourceWithCounter()) {
            List<Counted> reports = sinkAt(a);
            Process b = startPeer(a, "jvm-b");
            try {
                Management.migrate(a.node, "jvm-a", COUNTER, "jvm-b").get(60, TimeUnit.SECONDS);
                for (long i = 0; i < 5; i++) {
                    a.node.send(COUNTER, new Seq(i), SeqStream.QOS);
                }
                Await.until("five handled at B", () -> reports.size() == 5);

                int restoresBefore = ReportingCounter.SlowRestore.restoring.get();
                String classHere = slowRestore ? ReportingCounter.SlowRestore.class.getName() : null;
                var back = Management.migrate(a.node, "jvm-b", new MigrateRequest(COUNTER, "jvm-a", classHere, null,
                        null), Duration.ofSeconds(5));
                if (slowRestore) {
                    Await.until("the restore here began", () -> ReportingCounter.SlowRestore.restoring.get() > restoresBefore);
                } else {
                    Await.until("the state installed here", () -> !arrivalProfiles(a).isEmpty()
                            || resolveOrNull(a, COUNTER) instanceof Endpoint.Local);
                }
                b.destroyForcibly();
                assertTrue(b.waitFor(30, TimeUnit.SECONDS), "the source JVM is gone");
                Await.until("B seen gone without a goodbye", () -> a.net.goneWithoutGoodbye("jvm-b").isPresent());

                Await.until(() -> when + ": taken over " + a.management.takenOverInCount() + ", handed over "
                        + a.management.migratedInCount() + ", arrival profiles " + arrivalProfiles(a), 30_000,
                        () -> a.management.takenOverInCount() + a.management.migratedInCount() == 1
                                && arrivalProfiles(a).isEmpty());
                if (slowRestore) {
                    assertEquals(1, a.management.takenOverInCount(), "no hand-over can come: taken over");
                }
                assertEquals(0, a.management.abandonedInCount(), "not given up");
                assertInstanceOf(Endpoint.Local.class, a.node.registry().resolve(COUNTER), "it runs here");
                assertEquals(Shell.State.RUNNING, a.node.shell(COUNTER).state());
                a.node.send(COUNTER, new Seq(5), SeqStream.QOS);
                Await.until("the next one handled here", () -> reports.size() == 6);
                assertEquals(new Counted(5, 6), reports.getLast(), "counting on from the state handed over");
                if (slowRestore) {
                    var error = assertThrows(ExecutionException.class, () -> back.get(60, TimeUnit.SECONDS));
                    assertInstanceOf(RequestFailedException.class, error.getCause(), "the request to the dead"
                            + " node fails when it times out");
                }
            } finally {
                b.destroyForcibly();
            }
        }
    }

    /**
     * The source's INSTALL step times out (this node restores for 3 s, the step waits 2 s), so the
     * source resumes the counter and handles messages; then its JVM is killed (SIGKILL). Its
     * process left after it could have resumed the counter, so this node must not take its stale
     * copy over (the messages handled at the source since would be undone): it gives it up after
     * the hand-over wait, and the counter is gone with the node that last ran it.
     */
    @Test
    void shouldNotTakeOverACopyWhoseSourceResumedTheComponentBeforeItDied() throws Exception {
        try (var a = sourceWithCounter()) {
            List<Counted> reports = sinkAt(a);
            Process b = startPeer(a, "jvm-b");
            try {
                Management.migrate(a.node, "jvm-a", COUNTER, "jvm-b").get(60, TimeUnit.SECONDS);
                var back = Management.migrate(a.node, "jvm-b", new MigrateRequest(COUNTER, "jvm-a",
                        ReportingCounter.TooSlowRestore.class.getName(), null, null), Duration.ofSeconds(30));
                var error = assertThrows(ExecutionException.class, () -> back.get(60, TimeUnit.SECONDS));
                String why = assertInstanceOf(ManagementException.class, error.getCause()).failure().error();
                assertTrue(why.contains("resumed at 'jvm-b'"), why);
                a.node.send(COUNTER, new Seq(0), SeqStream.QOS); // handled at B, which runs it again
                Await.until("handled at B after it resumed", () -> reports.size() == 1);
                Await.until("the late copy installed here", () -> arrivalProfiles(a).size() == 1);

                b.destroyForcibly();
                assertTrue(b.waitFor(30, TimeUnit.SECONDS), "the source JVM is gone");
                Await.until("B seen gone without a goodbye", () -> a.net.goneWithoutGoodbye("jvm-b").isPresent());
                Await.until(() -> "given up: " + a.management.abandonedInCount() + ", taken over "
                        + a.management.takenOverInCount(), 30_000, () -> a.management.abandonedInCount() == 1);
                assertEquals(0, a.management.takenOverInCount(), "the stale copy was not taken over");
                assertEquals(List.of(), arrivalProfiles(a));
                assertTrue(!(resolveOrNull(a, COUNTER) instanceof Endpoint.Local), "this node does not run it");
            } finally {
                b.destroyForcibly();
            }
        }
    }

    /** Adds the counter's sink to {@code node}; returns the reports it collects. */
    private static List<Counted> sinkAt(MigrationNode node) {
        var reports = new CopyOnWriteArrayList<Counted>();
        node.node.add(ReportingCounter.SINK, () -> (message, context) -> reports.add((Counted) message.contents()));
        return reports;
    }

    private static List<Profile> arrivalProfiles(MigrationNode node) {
        return node.node.registry().profiles().stream()
                .filter(profile -> profile.role().equals("etherware.arrival")).toList();
    }

    private static Endpoint resolveOrNull(MigrationNode node, Profile profile) {
        try {
            return node.node.registry().resolve(profile);
        } catch (ProfileResolutionException e) {
            return null;
        }
    }
}
