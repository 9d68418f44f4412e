package io.etherware.services.management;

import static org.junit.jupiter.api.Assertions.assertEquals;

import example.counter.Counted;
import example.counter.ReportingCounter;
import example.counter.Seq;
import io.etherware.core.kernel.EtherwareNode;
import io.etherware.core.message.Criticality;
import io.etherware.core.message.Message;
import io.etherware.core.message.MessageId;
import io.etherware.core.message.Profile;
import io.etherware.core.message.QoS;
import io.etherware.testkit.Await;
import java.util.ArrayList;
import java.util.BitSet;
import java.util.Comparator;
import java.util.List;
import java.util.Map;
import java.util.concurrent.ConcurrentHashMap;
import java.util.concurrent.CopyOnWriteArrayList;
import java.util.concurrent.TimeUnit;
import java.util.concurrent.locks.LockSupport;

/**
 * A steady stream of sequence-numbered {@link Seq} messages from one node to a
 * {@link ReportingCounter}, and the sink that collects its reports, to check that a migration
 * loses, duplicates and reorders nothing.
 */
final class SeqStream implements AutoCloseable {

    static final QoS QOS = QoS.of(Criticality.MIDDLE);

    final List<Message> reports = new CopyOnWriteArrayList<>();
    /** The id each sequence number was sent under, for a failure to name. */
    private final Map<Long, MessageId> ids = new ConcurrentHashMap<>();
    private final EtherwareNode node;
    private final Profile target;
    private final long periodNs;
    private final int burst;
    private volatile boolean running = true;
    private volatile long sent;
    private final Thread sender;

    /** Adds the sink to {@code node} and starts sending to {@code target} every {@code periodNs}. */
    SeqStream(EtherwareNode node, Profile target, long periodNs) {
        this(node, target, periodNs, 1);
    }

    /**
     * Adds the sink to {@code node} and starts sending to {@code target} {@code burst} messages back
     * to back every {@code periodNs}: consecutive messages then leave microseconds apart, closer than
     * a network hop, which is what can overtake a message on a longer path.
     */
    SeqStream(EtherwareNode node, Profile target, long periodNs, int burst) {
        this.node = node;
        this.target = target;
        this.periodNs = periodNs;
        this.burst = burst;
        node.add(ReportingCounter.SINK, () -> (message, context) -> reports.add(message));
        this.sender = Thread.ofPlatform().daemon().name("seq-stream").start(this::send);
    }

    private void send() {
        long next = System.nanoTime();
        for (long i = 0; running; ) {
            for (int k = 0; k < burst; k++, i++) {
                ids.put(i, node.send(target, new Seq(i), QOS));
            }
            sent = i;
            next += periodNs;
            LockSupport.parkNanos(Math.max(0, next - System.nanoTime()));
        }
    }

    /** How many sent so far. */
    long sent() {
        return sent;
    }

    /** Waits until {@code count} more have been sent (bounded by the tests' deadline). */
    void awaitMore(long count) {
        long goal = sent + count;
        Await.until(goal + " messages sent", () -> sent >= goal);
    }

    /** Waits until every message sent so far was handled and reported (bounded by the tests' deadline). */
    void awaitCaughtUp() {
        long goal = sent;
        Await.until("the " + goal + " messages sent so far reported", () -> reports.size() >= goal);
    }

    /** Stops, waits for a report of every message sent, and checks that there is one each. */
    private List<Counted> stopAndAwaitEveryReport() throws InterruptedException {
        long total = stop();
        Await.until(total + " reports (have " + reports.size() + ")", () -> reports.size() >= total);
        List<Counted> handled = handled();
        assertEquals(total, handled.size(), "each message handled exactly once");
        return handled;
    }

    /** Stops sending; returns how many were sent. */
    long stop() throws InterruptedException {
        running = false;
        sender.join(TimeUnit.SECONDS.toMillis(30));
        return sent;
    }

    /** The reports in handling order (by count). */
    List<Counted> handled() {
        var counted = new ArrayList<Counted>();
        for (Message report : reports) {
            counted.add((Counted) report.contents());
        }
        counted.sort(Comparator.comparingLong(Counted::count));
        return counted;
    }

    /** The nodes that handled the messages, in handling order, each run of one node once. */
    List<String> handlers() {
        var sorted = new ArrayList<>(reports);
        sorted.sort(Comparator.comparingLong(report -> ((Counted) report.contents()).count()));
        var nodes = new ArrayList<String>();
        for (Message report : sorted) {
            String handler = report.messageId().nodeId();
            if (nodes.isEmpty() || !nodes.getLast().equals(handler)) {
                nodes.add(handler);
            }
        }
        return nodes;
    }

    /** Stops, waits for every report, and checks: each message handled once, in order, the count continuing. */
    void stopAndAssertExactlyOnceInOrder() throws InterruptedException {
        List<Counted> handled = stopAndAwaitEveryReport();
        for (int i = 0; i < handled.size(); i++) {
            Counted counted = handled.get(i);
            if (counted.count() != i + 1 || counted.sequence() != i) {
                throw new AssertionError("the " + (i + 1) + "th handling was " + counted + ": expected sequence " + i
                        + " as count " + (i + 1) + " (lost, duplicated or reordered, or the count did not continue);"
                        + " handlings around it: " + around(i) + "; sequence " + i + " was handled " + whereIs(i));
            }
        }
    }

    /**
     * Stops, waits for every report, and checks: each message handled exactly once, the count
     * continuing, and at most {@code maxLate} messages handled after a later one of the stream.
     *
     * @return how many were handled after a later one
     */
    int stopAndAssertExactlyOnceAtMostLate(int maxLate) throws InterruptedException {
        List<Counted> handled = stopAndAwaitEveryReport();
        long total = handled.size();
        var seen = new BitSet();
        long highest = -1;
        var late = new ArrayList<String>();
        for (int i = 0; i < handled.size(); i++) {
            Counted counted = handled.get(i);
            if (counted.count() != i + 1) {
                throw new AssertionError("the " + (i + 1) + "th handling has count " + counted.count()
                        + ": the count did not continue; handlings around it: " + around(i));
            }
            int sequence = Math.toIntExact(counted.sequence());
            if (sequence >= total || seen.get(sequence)) {
                throw new AssertionError("sequence " + sequence + " handled twice or never sent: " + around(i));
            }
            seen.set(sequence);
            if (sequence < highest) {
                late.add("sequence " + sequence + " handled after " + highest + ":" + around(i) + "; sent as "
                        + ids.get((long) sequence));
            }
            highest = Math.max(highest, sequence);
        }
        if (late.size() > maxLate) {
            throw new AssertionError(late.size() + " messages handled after a later one (at most " + maxLate
                    + " allowed): " + late.subList(0, Math.min(5, late.size())));
        }
        return late.size();
    }

    private String whereIs(long sequence) {
        var text = new StringBuilder();
        for (Message report : reports) {
            Counted counted = (Counted) report.contents();
            if (counted.sequence() == sequence) {
                text.append(" as count ").append(counted.count()).append(" at ").append(report.messageId().nodeId());
            }
        }
        return (text.isEmpty() ? "never" : text.toString().strip()) + " (sent as " + ids.get(sequence)
                + ", the next as " + ids.get(sequence + 1) + ")";
    }

    private String around(int index) {
        var sorted = new ArrayList<>(reports);
        sorted.sort(Comparator.comparingLong(report -> ((Counted) report.contents()).count()));
        var text = new StringBuilder();
        for (int i = Math.max(0, index - 3); i < Math.min(sorted.size(), index + 4); i++) {
            Message report = sorted.get(i);
            Counted counted = (Counted) report.contents();
            text.append(" #").append(counted.count()).append(" seq ").append(counted.sequence()).append(" at ")
                    .append(report.messageId().nodeId());
        }
        return text.toString();
    }

    @Override
    public void close() throws InterruptedException {
        stop();
    }
}
