package io.etherware.services.network;

import io.etherware.core.component.RequestFailedException;
import io.etherware.core.kernel.EtherwareNode;
import io.etherware.core.message.Criticality;
import io.etherware.core.message.Message;
import io.etherware.core.message.Profile;
import io.etherware.core.message.QoS;
import io.etherware.testkit.Await;
import java.util.ArrayList;
import java.util.EnumMap;
import java.util.List;
import java.util.Map;
import java.util.concurrent.ConcurrentLinkedQueue;
import java.util.concurrent.Executors;
import java.util.concurrent.ScheduledExecutorService;
import java.util.concurrent.TimeUnit;
import java.util.concurrent.atomic.AtomicLong;

/**
 * The legitimate peer's traffic in the hostile-peer tests: one HIGH request every 10 ms from a
 * node to a component that echoes its {@link Num}, each with a bounded timeout, every outcome
 * counted: answered (the reply carries the request's own number), wrong (a reply with anything
 * else), failed (by {@link RequestFailedException.Reason}, with the index of the request).
 *
 * <p>Thread-safety: started and stopped by the test thread; outcomes are counted on kernel threads.
 */
final class LegitLoad implements AutoCloseable {

    static final long PERIOD_MS = 10;
    private static final QoS HIGH = QoS.of(Criticality.HIGH);

    /** One failed request: its index in sending order, why, and the kernel's words. */
    record Failure(long index, RequestFailedException.Reason reason, String detail) {
    }

    private final EtherwareNode node;
    private final Profile to;
    private final long timeoutNs;
    private final ScheduledExecutorService timer = Executors.newSingleThreadScheduledExecutor(task ->
            Thread.ofPlatform().daemon().name("legit-load").unstarted(task));
    private final AtomicLong sent = new AtomicLong();
    private final AtomicLong answered = new AtomicLong();
    private final AtomicLong wrong = new AtomicLong();
    private final ConcurrentLinkedQueue<Failure> failures = new ConcurrentLinkedQueue<>();
    /** Set and read on the timer thread only. */
    private boolean paused;

    private LegitLoad(EtherwareNode node, Profile to, long timeoutNs) {
        this.node = node;
        this.to = to;
        this.timeoutNs = timeoutNs;
    }

    /** Starts requesting {@code to} from {@code node}, each request failing after {@code timeoutMs}. */
    static LegitLoad start(EtherwareNode node, Profile to, long timeoutMs) {
        var load = new LegitLoad(node, to, TimeUnit.MILLISECONDS.toNanos(timeoutMs));
        load.timer.scheduleAtFixedRate(load::requestOne, 0, PERIOD_MS, TimeUnit.MILLISECONDS);
        return load;
    }

    /**
     * Stops sending until {@link #resume}: when this returns, no request is being sent and none will
     * be, so {@link #pending()} counts exactly the requests exposed to what happens next.
     */
    void pause() throws Exception {
        timer.submit(() -> paused = true).get(10, TimeUnit.SECONDS);
    }

    /** Sends again, one request per period. */
    void resume() throws Exception {
        timer.submit(() -> paused = false).get(10, TimeUnit.SECONDS);
    }

    private void requestOne() {
        if (paused) {
            return;
        }
        long index = sent.getAndIncrement();
        var request = new Message(to, node.profile(), node.clock().epochNanos(), HIGH, new Num(index),
                node.newMessageId(), null);
        try {
            node.request(request, timeoutNs).whenComplete((reply, error) -> {
                if (error == null) {
                    (new Num(index).equals(reply.contents()) ? answered : wrong).incrementAndGet();
                } else {
                    failures.add(failure(index, error));
                }
            });
        } catch (RuntimeException e) {
            failures.add(failure(index, e));
        }
    }

    private static Failure failure(long index, Throwable error) {
        Throwable cause = error instanceof java.util.concurrent.CompletionException && error.getCause() != null
                ? error.getCause() : error;
        var reason = cause instanceof RequestFailedException failed ? failed.reason() : null;
        return new Failure(index, reason, cause.toString());
    }

    /** Requests sent so far. */
    long sent() {
        return sent.get();
    }

    long answered() {
        return answered.get();
    }

    /** Requests without an outcome yet. */
    long pending() {
        return sent.get() - answered.get() - wrong.get() - failures.size();
    }

    List<Failure> failures() {
        return new ArrayList<>(failures);
    }

    /** Failures by reason. */
    Map<RequestFailedException.Reason, Long> failuresByReason() {
        var byReason = new EnumMap<RequestFailedException.Reason, Long>(RequestFailedException.Reason.class);
        for (Failure failure : failures) {
            if (failure.reason != null) {
                byReason.merge(failure.reason, 1L, Long::sum);
            }
        }
        return byReason;
    }

    long failed(RequestFailedException.Reason reason) {
        return failuresByReason().getOrDefault(reason, 0L);
    }

    /**
     * Stops sending and waits until every request sent has its outcome: answered, or failed at
     * the latest by its own timeout (so "never hangs" is checked by the wait itself).
     */
    LegitLoad stop() {
        timer.shutdown();
        try {
            if (!timer.awaitTermination(5, TimeUnit.SECONDS)) {
                throw new AssertionError("the load's timer did not stop");
            }
        } catch (InterruptedException e) {
            Thread.currentThread().interrupt();
            throw new AssertionError(e);
        }
        long graceMs = TimeUnit.NANOSECONDS.toMillis(timeoutNs) + Await.DEADLINE_MS;
        Await.until("every request of the legitimate peer has an outcome (" + this + ")", graceMs,
                () -> pending() == 0);
        return this;
    }

    @Override
    public void close() {
        timer.shutdownNow();
    }

    @Override
    public String toString() {
        return "legit load: sent=" + sent.get() + " answered=" + answered.get() + " wrong=" + wrong.get()
                + " failed=" + failuresByReason() + " " + failures.stream().limit(5).toList();
    }
}
