package io.etherware.services.management;

import static org.junit.jupiter.api.Assertions.assertEquals;
import static org.junit.jupiter.api.Assertions.assertInstanceOf;
import static org.junit.jupiter.api.Assertions.assertNotEquals;
import static org.junit.jupiter.api.Assertions.assertTrue;

import example.counter.CounterState;
import example.counter.Journal;
import example.counter.SequenceCounter;
import example.counter.SequenceCounterV2;
import example.counter.Seq;
import io.etherware.core.component.Shell;
import io.etherware.core.kernel.EtherwareNode;
import io.etherware.core.message.Criticality;
import io.etherware.core.message.Profile;
import io.etherware.core.message.QoS;
import io.etherware.core.scheduler.FifoScheduler;
import io.etherware.core.scheduler.Scheduler;
import io.etherware.rt.scheduling.RealtimeScheduler;
import io.etherware.rt.scheduling.RealtimeSchedulerConfig;
import io.etherware.rt.scheduling.ThreadSchedulingRule;
import io.etherware.testkit.Await;
import java.io.IOException;
import java.nio.file.Files;
import java.nio.file.Path;
import java.util.List;
import java.util.Map;
import java.util.concurrent.ExecutionException;
import java.util.concurrent.TimeUnit;
import java.util.concurrent.atomic.AtomicLong;
import java.util.concurrent.locks.LockSupport;
import java.util.function.Supplier;
import java.util.stream.LongStream;
import org.junit.jupiter.api.Test;
import org.junit.jupiter.api.io.TempDir;
import org.junit.jupiter.params.ParameterizedTest;
import org.junit.jupiter.params.provider.ValueSource;

/**
 * Upgrades through the management service: under a stream, from (signed) jars, rolled back,
 * refused. The signatures themselves are {@link UpgradeSignatureIT}'s subject.
 */
class UpgradeIT {

    static final Profile COUNTER = Profile.parse("counter[loop=1]");
    private static final long PERIOD_NS = TimeUnit.MILLISECONDS.toNanos(1);

    @TempDir
    Path allowed;

    static Supplier<Scheduler> scheduler(String name) {
        return switch (name) {
            case "fifo" -> FifoScheduler::new;
            case "rt" -> () -> new RealtimeScheduler(RealtimeSchedulerConfig.builder()
                    .threadSchedulingRule(ThreadSchedulingRule.nonRealtime(4)).build());
            default -> throw new IllegalArgumentException(name);
        };
    }

    EtherwareNode node(String nodeId, Supplier<Scheduler> scheduler, Journal journal, String journalName)
            throws IOException {
        var node = EtherwareNode.builder().nodeId(nodeId).scheduler(scheduler).build();
        ManagementService.install(node, ManagementConfig.builder().allowDirectory(allowed)
                .trustedSigner(JarBuilder.testKey().certificate()).build());
        node.add(COUNTER, () -> new SequenceCounter(journalName));
        return node.start();
    }

    @ParameterizedTest
    @ValueSource(strings = {"fifo", "rt"})
    void shouldLoseDuplicateOrReorderNoMessageWhenUpgradedUnderA1kHzStream(String schedulerName) throws Exception {
        String name = "stream-" + schedulerName;
        Journal journal = Journal.create(name);
        try (var node = node("upgrade-" + schedulerName, scheduler(schedulerName), journal, name)) {
            var stream = new Stream(node);
            Await.until("the stream is flowing", () -> journal.size() >= 300);

            long beforeNs = System.nanoTime(); // the node's clock: NodeClock.system()
            UpgradeResult result = Management.upgrade(node, node.nodeId(), COUNTER,
                            Implementation.ofClass(SequenceCounterV2.class).withConfiguration(name))
                    .get(30, TimeUnit.SECONDS);
            long callNs = System.nanoTime() - beforeNs;
            int total = stream.finish(300);
            Await.until("every message handled", () -> journal.size() == total);

            List<Journal.Entry> entries = journal.entries();
            assertExactlyOnceInOrder(entries, total);
            long v1 = entries.stream().takeWhile(entry -> entry.version().equals("v1")).count();
            assertTrue(v1 >= 300 && v1 < total, "v1 handled the start of the stream: " + v1);
            assertTrue(entries.subList((int) v1, total).stream().allMatch(entry -> entry.version().equals("v2")),
                    "after the swap only the new logic runs");
            assertEquals(SequenceCounterV2.class, node.shell(COUNTER).logicType());

            assertEquals(COUNTER, result.target());
            assertEquals(SequenceCounter.class.getName(), result.oldImplementation());
            assertEquals(SequenceCounterV2.class.getName(), result.newImplementation());
            assertEquals(UpgradeResult.CLASSPATH, result.source());
            assertEquals(CounterState.SCHEMA_VERSION, result.stateSchemaVersion());
            // Measured, each within the one before: load and pause within the total, the total
            // within the call, the pause within the gap.
            assertTrue(result.loadNs() > 0 && result.pauseNs() > 0, "load and pause measured: " + result);
            assertTrue(result.loadNs() + result.pauseNs() <= result.totalNs(),
                    "the total contains the load and the pause: " + result);
            assertTrue(result.totalNs() <= callNs, "the total is within the call's " + callNs + " ns: " + result);
            assertTrue(result.gapNs() >= result.pauseNs(), "the gap contains the pause: " + result);
            assertEquals(0, node.stats().undeliverable());
        }
    }

    @Test
    void shouldRunANewVersionOfAClassFromAnAllowlistedJarWhenTheJarAlsoCarriesTheStateRecord() throws Exception {
        // The jar carries its own SequenceCounterV2 (the node has one too) and a copy of the state
        // record: the jar's logic must win, the state record must stay the node's.
        Path jar = JarBuilder.buildSigned(allowed.resolve("counter-v2-jar.jar"), Map.of(
                "example.counter.SequenceCounterV2", """
                        package example.counter;
                        public class SequenceCounterV2 extends SequenceCounter {
                            public SequenceCounterV2(String journalName) { super(journalName); }
                            @Override protected String version() { return "v2-jar"; }
                        }
                        """,
                "example.counter.CounterState", """
                        package example.counter;
                        public record CounterState(long count, long lastSequence)
                                implements io.etherware.core.component.ComponentState {
                            @Override public int schemaVersion() { return 2; }
                        }
                        """));
        Journal journal = Journal.create("jar");
        try (var node = node("upgrade-jar", FifoScheduler::new, journal, "jar")) {
            sendAndAwait(node, journal, 0, 3);
            UpgradeResult result = Management.upgrade(node, node.nodeId(), COUNTER,
                    Implementation.fromJar(jar, "example.counter.SequenceCounterV2").withConfiguration("jar"))
                    .get(30, TimeUnit.SECONDS);
            sendAndAwait(node, journal, 3, 6);

            assertEquals(List.of("v1", "v1", "v1", "v2-jar", "v2-jar", "v2-jar"),
                    journal.entries().stream().map(Journal.Entry::version).toList());
            assertEquals(List.of(1L, 2L, 3L, 4L, 5L, 6L), journal.entries().stream().map(Journal.Entry::count).toList());
            Class<?> running = node.shell(COUNTER).logicType();
            assertEquals(SequenceCounterV2.class.getName(), running.getName());
            assertNotEquals(SequenceCounterV2.class, running, "the jar's version, not the class path's");
            assertEquals(jar.toRealPath().toString(), result.source());
        }
    }

    @Test
    void shouldRollBackAndKeepServingWithNothingLostWhenTheNewLogicsRestoreThrowsUnderAStream() throws Exception {
        Path jar = JarBuilder.buildSigned(allowed.resolve("counter-broken.jar"), Map.of(
                "broken.CounterV3", """
                        package broken;
                        public class CounterV3 extends example.counter.SequenceCounter {
                            public CounterV3(String journalName) { super(journalName); }
                            @Override public void restore(io.etherware.core.component.ComponentState state) {
                                throw new IllegalStateException("CounterV3 cannot read state schema "
                                        + state.schemaVersion());
                            }
                        }
                        """));
        Journal journal = Journal.create("broken");
        try (var node = node("upgrade-broken", FifoScheduler::new, journal, "broken")) {
            var stream = new Stream(node);
            Await.until("the stream is flowing", () -> journal.size() >= 100);
            var failure = assertInstanceOf(ManagementException.class, assertFailed(Management.upgrade(node,
                    node.nodeId(), COUNTER, Implementation.fromJar(jar, "broken.CounterV3").withConfiguration("broken"))));
            assertEquals(ManagementFailure.Reason.ROLLED_BACK, failure.reason());
            assertTrue(failure.getMessage().contains("CounterV3 cannot read state schema 2"), failure.getMessage());
            assertTrue(failure.getMessage().contains(SequenceCounter.class.getName() + " serves on"),
                    failure.getMessage());

            int total = stream.finish(100);
            Await.until("every message handled", () -> journal.size() == total);
            assertExactlyOnceInOrder(journal.entries(), total);
            assertTrue(journal.entries().stream().allMatch(entry -> entry.version().equals("v1")), "the old logic served");
            assertEquals(SequenceCounter.class, node.shell(COUNTER).logicType());
            assertEquals(Shell.State.RUNNING, node.shell(COUNTER).state());
        }
    }

    @Test
    void shouldRefuseAJarOutsideTheAllowlistWhetherNamedDirectlyOrThroughALink(@TempDir Path elsewhere)
            throws Exception {
        Path outside = JarBuilder.build(elsewhere.resolve("evil.jar"), Map.of("evil.Counter", """
                package evil;
                public class Counter extends example.counter.SequenceCounter {
                    public Counter(String journalName) { super(journalName); }
                }
                """));
        Path link = Files.createSymbolicLink(allowed.resolve("innocent.jar"), outside);
        Path dotDot = allowed.resolve("..").resolve(elsewhere.getFileName()).resolve("evil.jar");
        Journal journal = Journal.create("refuse");
        try (var node = node("upgrade-refuse", FifoScheduler::new, journal, "refuse")) {
            for (Path jar : List.of(outside, link, dotDot)) {
                var failure = assertInstanceOf(ManagementException.class, assertFailed(Management.upgrade(node,
                        node.nodeId(), COUNTER, Implementation.fromJar(jar, "evil.Counter").withConfiguration("refuse"))));
                assertEquals(ManagementFailure.Reason.CODE_NOT_ALLOWED, failure.reason(), failure.getMessage());
                assertTrue(failure.getMessage().contains(jar.toString()), failure.getMessage());
                assertTrue(failure.getMessage().contains("outside the allowlisted directories"), failure.getMessage());
            }
            assertEquals(SequenceCounter.class, node.shell(COUNTER).logicType());
            sendAndAwait(node, journal, 0, 1);
        }
    }

    @Test
    void shouldAnswerWithTheReasonWhenTheImplementationCannotBeUsed() throws Exception {
        Path jar = JarBuilder.buildSigned(allowed.resolve("contract.jar"), Map.of(
                "contract.NotAComponent", "package contract; public class NotAComponent { }",
                "contract.NoConstructor", """
                        package contract;
                        public class NoConstructor extends example.counter.SequenceCounter {
                            public NoConstructor(int wrong) { super("contract"); }
                        }
                        """,
                "contract.Hidden", """
                        package contract;
                        class Hidden extends example.counter.SequenceCounter {
                            public Hidden(String journalName) { super(journalName); }
                        }
                        """,
                "contract.Exploding", """
                        package contract;
                        public class Exploding extends example.counter.SequenceCounter {
                            public Exploding(String journalName) {
                                super(journalName);
                                throw new IllegalArgumentException("bad gains: " + journalName);
                            }
                        }
                        """));
        Journal journal = Journal.create("contract");
        try (var node = node("upgrade-contract", FifoScheduler::new, journal, "contract")) {
            record Case(Implementation implementation, ManagementFailure.Reason reason, String says) {
            }
            for (Case each : List.of(
                    new Case(Implementation.fromJar(jar, "contract.NotAComponent"),
                            ManagementFailure.Reason.INVALID_IMPLEMENTATION, "does not implement"),
                    new Case(Implementation.fromJar(jar, "contract.NoConstructor").withConfiguration("contract"),
                            ManagementFailure.Reason.INVALID_IMPLEMENTATION, "constructor (String configuration)"),
                    new Case(Implementation.fromJar(jar, "contract.Hidden").withConfiguration("contract"),
                            ManagementFailure.Reason.INVALID_IMPLEMENTATION, "must be public"),
                    new Case(Implementation.fromJar(jar, "contract.Exploding").withConfiguration("contract"),
                            ManagementFailure.Reason.CONSTRUCTION_FAILED, "bad gains: contract"),
                    new Case(Implementation.fromJar(jar, "contract.Missing"),
                            ManagementFailure.Reason.CLASS_NOT_LOADABLE, "not found in jar"),
                    new Case(Implementation.fromJar(allowed.resolve("absent.jar"), "contract.Missing"),
                            ManagementFailure.Reason.CLASS_NOT_LOADABLE, "does not exist"),
                    new Case(Implementation.fromJar(jar, SequenceCounterV2.class.getName()),
                            ManagementFailure.Reason.CLASS_NOT_LOADABLE, "is not in jar"),
                    new Case(Implementation.ofClass("no such class"),
                            ManagementFailure.Reason.BAD_REQUEST, "not a binary class name"),
                    new Case(Implementation.ofClass("com.example.Absent"),
                            ManagementFailure.Reason.CLASS_NOT_LOADABLE, "not found on the class path"))) {
                var failure = assertInstanceOf(ManagementException.class,
                        assertFailed(Management.upgrade(node, node.nodeId(), COUNTER, each.implementation())));
                assertEquals(each.reason(), failure.reason(), failure.getMessage());
                assertTrue(failure.getMessage().contains(each.says()), failure.getMessage());
            }
            var unknown = assertInstanceOf(ManagementException.class, assertFailed(Management.upgrade(node,
                    node.nodeId(), Profile.of("nobody"), Implementation.ofClass(SequenceCounterV2.class))));
            assertEquals(ManagementFailure.Reason.UNKNOWN_COMPONENT, unknown.reason());
            assertEquals(SequenceCounter.class, node.shell(COUNTER).logicType());
            sendAndAwait(node, journal, 0, 1);
        }
    }

    @Test
    void shouldAnswerARequesterComponentOnItsOwnDispatcherWhenItAsksForAnUpgrade() throws Exception {
        Journal journal = Journal.create("requester");
        var answered = new java.util.concurrent.CompletableFuture<UpgradeResult>();
        var answeredOnDispatcher = new java.util.concurrent.atomic.AtomicBoolean();
        try (var node = node("upgrade-requester", FifoScheduler::new, journal, "requester")) {
            node.add(Profile.of("requester"), () -> (message, context) ->
                    Management.upgrade(context, "upgrade-requester", COUNTER,
                                    Implementation.ofClass(SequenceCounterV2.class).withConfiguration("requester"))
                            .whenComplete((result, error) -> {
                                answeredOnDispatcher.set(Thread.currentThread().getName().startsWith("etherware-fifo@"));
                                if (error != null) {
                                    answered.completeExceptionally(error);
                                } else {
                                    answered.complete(result);
                                }
                            }));
            sendAndAwait(node, journal, 0, 1);
            node.send(Profile.of("requester"), new io.etherware.core.message.Text("upgrade the counter"));
            Await.until("the swap", () -> node.shell(COUNTER).logicType() == SequenceCounterV2.class);
            sendAndAwait(node, journal, 1, 2);
            UpgradeResult result = answered.get(30, TimeUnit.SECONDS);
            assertEquals(SequenceCounterV2.class.getName(), result.newImplementation());
            assertTrue(result.gapNs() > 0, "measured from the old logic's last message to the new one's first");
            assertTrue(answeredOnDispatcher.get(), "a component's request completes on its dispatcher");
            assertEquals(List.of("v1", "v2"), journal.entries().stream().map(Journal.Entry::version).toList());
        }
    }

    /** Sends {@code total} sequence numbers at 1 kHz from a thread of its own (absolute release times). */
    /**
     * A 1 kHz stream of sequence numbers that runs until {@link Stream#finish} says how many more
     * to send, so that a slow machine cannot end the stream before the upgrade has happened.
     */
    static final class Stream {
        private static final long MAX_MESSAGES = 60_000;
        private final AtomicLong sent = new AtomicLong();
        private final AtomicLong limit = new AtomicLong(MAX_MESSAGES);
        private final Thread sender;

        Stream(EtherwareNode node) {
            sender = Thread.ofPlatform().name("sender-1kHz").start(() -> {
                long nextNs = System.nanoTime();
                for (long i = 0; i < limit.get(); i++) {
                    node.send(COUNTER, new Seq(i), QoS.periodic(Criticality.MIDDLE, PERIOD_NS));
                    sent.set(i + 1);
                    nextNs += PERIOD_NS;
                    LockSupport.parkNanos(nextNs - System.nanoTime());
                }
            });
        }

        /** Sends {@code more} messages after the ones already sent, then stops; returns the total. */
        int finish(int more) throws InterruptedException {
            assertTrue(sender.isAlive(), "the stream was still running when the upgrade ended");
            limit.set(sent.get() + more);
            sender.join();
            return Math.toIntExact(sent.get());
        }
    }

    /** Every sequence number once, in order, and the count in the state never restarted. */
    static void assertExactlyOnceInOrder(List<Journal.Entry> entries, int total) {
        assertEquals(LongStream.range(0, total).boxed().toList(),
                entries.stream().map(Journal.Entry::sequence).toList(), "none lost, duplicated or reordered");
        assertEquals(LongStream.rangeClosed(1, total).boxed().toList(),
                entries.stream().map(Journal.Entry::count).toList(), "the count continues across the swap");
    }

    static void sendAndAwait(EtherwareNode node, Journal journal, long from, long to) {
        for (long i = from; i < to; i++) {
            node.send(COUNTER, new Seq(i));
        }
        Await.until("messages up to " + to, () -> journal.size() == to);
    }

    static Throwable assertFailed(java.util.concurrent.Future<?> future) throws Exception {
        try {
            Object value = future.get(30, TimeUnit.SECONDS);
            throw new AssertionError("expected a failure, got " + value);
        } catch (ExecutionException e) {
            return e.getCause();
        }
    }
}
