package io.etherware.services.management;

import static org.junit.jupiter.api.Assertions.assertEquals;
import static org.junit.jupiter.api.Assertions.assertInstanceOf;
import static org.junit.jupiter.api.Assertions.assertThrows;
import static org.junit.jupiter.api.Assertions.assertTrue;

import example.counter.ReportingCounter;
import io.etherware.core.component.RequestFailedException;
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
import java.util.concurrent.CompletableFuture;
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
 * PREPARE or the INSTALL step of a migration, the counter resumes at the source with nothing lost;
 * when the source JVM is killed inside the PREPARE, snapshot or INSTALL step, the target gives the
 * migration up and keeps nothing of it.
 */
class MigrationAcrossJvmsIT {

    private static final Profile COUNTER = Profile.parse("counter[test=jvm-migration]");
    private static final long STREAM_PERIOD_NS = TimeUnit.MICROSECONDS.toNanos(500);
    private static final Duration STEP_TIMEOUT = Duration.ofSeconds(2);

    @TempDir
    Path logs;

    /** The other JVM, connected to {@code a} once this returns. */
    private Process startPeer(MigrationNode a, String nodeId) throws IOException, InterruptedException {
        String classPath = System.getProperty("surefire.test.class.path", System.getProperty("java.class.path"));
        var command = List.of(Path.of(System.getProperty("java.home"), "bin", "java").toString(),
                "--enable-native-access=ALL-UNNAMED", "-cp", classPath, MigrationPeer.class.getName(), nodeId,
                "127.0.0.1", String.valueOf(a.address().getPort()), String.valueOf(STEP_TIMEOUT.toMillis()),
                a.node.nodeId());
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
     * The source JVM is killed (SIGKILL) inside a step of a migration to this JVM: while this node
     * constructs the new instance (PREPARE), while the source takes the state (the snapshot), or
     * while this node restores it (INSTALL). The component dies with its node, as it would without
     * a migration (no hand-over came, so this node must not run it); this node gives
     * the migration up after its waits, counts it as abandoned, and keeps nothing of it: no
     * prepared instance, no held copy, no arrival profile.
     */
    @ParameterizedTest(name = "source killed in {0}")
    @CsvSource(nullValues = "none", value = {
        "PREPARE, none, example.counter.ReportingCounter$SlowConstruct",
        "SNAPSHOT, example.counter.ReportingCounter$SlowSnapshot, none",
        "INSTALL, none, example.counter.ReportingCounter$SlowRestore"})
    void shouldKeepNothingOfTheMigrationWhenTheSourceJvmIsKilledDuringAStep(String step, String classAtSource,
            String classHere) throws Exception {
        try (var a = sourceWithCounter()) {
            Process b = startPeer(a, "jvm-b");
            try {
                Management.migrate(a.node, "jvm-a", new MigrateRequest(COUNTER, "jvm-b", classAtSource, null, null),
                        Duration.ofSeconds(60)).get(60, TimeUnit.SECONDS);
                assertInstanceOf(Endpoint.Remote.class, a.node.registry().resolve(COUNTER), "B hosts the counter");

                // B moves it back here, and dies in the middle.
                int restoresBefore = ReportingCounter.SlowRestore.restoring.get();
                var back = Management.migrate(a.node, "jvm-b", new MigrateRequest(COUNTER, "jvm-a", classHere, null,
                        null), Duration.ofSeconds(5));
                if (step.equals("INSTALL")) {
                    Await.until("the restore here began", () -> ReportingCounter.SlowRestore.restoring.get() > restoresBefore);
                } else {
                    Thread.sleep(500); // inside the 1.5 s step
                }
                b.destroyForcibly();
                assertTrue(b.waitFor(30, TimeUnit.SECONDS), "the source JVM is gone");
                if (step.equals("INSTALL")) {
                    Await.until("the held copy registered here", () -> arrivalProfiles(a).size() == 1);
                }

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
