package io.etherware.core.kernel.internal;

import io.etherware.core.component.RequestFailedException;
import io.etherware.core.component.RequestFailedException.Reason;
import io.etherware.core.kernel.RequestFailed;
import io.etherware.core.kernel.Undeliverable;
import io.etherware.core.message.Message;
import io.etherware.core.message.MessageId;
import io.etherware.core.message.Origin;
import java.util.LinkedHashSet;
import java.util.Map;
import java.util.concurrent.CompletableFuture;
import java.util.concurrent.ConcurrentHashMap;
import java.util.concurrent.ExecutionException;
import java.util.concurrent.RejectedExecutionException;
import java.util.concurrent.ScheduledThreadPoolExecutor;
import java.util.concurrent.TimeUnit;
import java.util.concurrent.TimeoutException;
import java.util.concurrent.atomic.LongAdder;
import java.util.function.BiPredicate;
import java.util.function.Consumer;
import org.slf4j.Logger;
import org.slf4j.LoggerFactory;

/**
 * The requests of a node that wait for their replies: sending them, correlation by request id,
 * timeouts on one shared timer thread, late replies counted and dropped.
 *
 * <p>Exactly one of reply, timeout and close settles a request: whichever removes it from the
 * table first. A reply that finds its request gone because it timed out is a late reply; the
 * table remembers the most recent timed-out ids (a bounded number) to tell late replies from
 * replies to plain messages, which are delivered like any message.
 *
 * <p>Thread-safety: all methods may be called from any thread.
 */
final class RequestTable {

    private static final Logger log = LoggerFactory.getLogger(RequestTable.class);
    /** How many timed-out request ids are remembered to recognize late replies. */
    private static final int TIMED_OUT_MEMORY = 4096;
    /** Extra wait of a blocking request beyond its timeout, for the timer thread to fire. */
    private static final long BLOCKING_GRACE_NS = TimeUnit.SECONDS.toNanos(5);

    private final String nodeId;
    private final Consumer<PendingRequest> outcomeSink;
    private final ConcurrentHashMap<MessageId, PendingRequest> pending = new ConcurrentHashMap<>();
    private final LinkedHashSet<MessageId> timedOut = new LinkedHashSet<>();
    private final ScheduledThreadPoolExecutor timer;
    private final LongAdder timeouts = new LongAdder();
    private final LongAdder lateReplies = new LongAdder();
    private final LongAdder foreignReplies = new LongAdder();
    /** Whether a node (by id) may answer a request (its message): where the request was routed. */
    private final BiPredicate<Message, String> mayAnswer;
    /** The kernel's send, for the requests. */
    private final Consumer<Message> sendMessage;

    /**
     * @param outcomeSink hands a settled-to-be request to its requester (a job for a component,
     *                    or {@link PendingRequest#settle()} directly)
     * @param sendMessage the kernel's send
     */
    RequestTable(String nodeId, Consumer<PendingRequest> outcomeSink, BiPredicate<Message, String> mayAnswer,
                 Consumer<Message> sendMessage) {
        this.nodeId = nodeId;
        this.outcomeSink = outcomeSink;
        this.mayAnswer = mayAnswer;
        this.sendMessage = sendMessage;
        this.timer = new ScheduledThreadPoolExecutor(1, runnable -> {
            Thread thread = new Thread(runnable, "etherware-timer-" + nodeId);
            thread.setDaemon(true);
            return thread;
        });
        timer.setRemoveOnCancelPolicy(true);
        timer.setExecuteExistingDelayedTasksAfterShutdownPolicy(false);
        // Started now, by the thread that builds the node, not by the first requester: started by
        // a real-time dispatcher, it would inherit that dispatcher's CPUs and wait behind it there,
        // runnable, holding up every safepoint of the JVM (seen with the CPUs partitioned).
        timer.prestartCoreThread();
    }

    /**
     * Sends a request; the outcome is delivered as a job of {@code requester} (null: completed on
     * the thread that has it).
     */
    CompletableFuture<Message> send(Message request, LocalShell requester, long timeoutNs) {
        if (timeoutNs <= 0) {
            throw new IllegalArgumentException("timeoutNs=" + timeoutNs + " must be > 0");
        }
        if (request.sender() == null) {
            throw new IllegalArgumentException("request " + request.messageId() + " needs a sender for its reply");
        }
        PendingRequest entry = register(request, requester, timeoutNs);
        try {
            sendMessage.accept(request);
        } catch (RuntimeException e) {
            cancel(entry);
            throw e;
        }
        return entry.future;
    }

    /**
     * Waits for {@code reply}, the outcome of request {@code id} sent with {@code timeoutNs}, on the
     * calling thread (which must not be a dispatcher).
     *
     * @throws RequestFailedException if the outcome is a failure, or none comes
     */
    static Message await(CompletableFuture<Message> reply, MessageId id, long timeoutNs) {
        try {
            return reply.get(timeoutNs + BLOCKING_GRACE_NS, TimeUnit.NANOSECONDS);
        } catch (InterruptedException e) {
            Thread.currentThread().interrupt();
            throw new RequestFailedException(Reason.INTERRUPTED, id, "interrupted while waiting for the reply to " + id, e);
        } catch (ExecutionException e) {
            if (e.getCause() instanceof RequestFailedException failure) {
                throw new RequestFailedException(failure.reason(), id, failure.getMessage(), failure);
            }
            throw new IllegalStateException("request " + id + " failed", e.getCause());
        } catch (TimeoutException e) {
            throw new RequestFailedException(Reason.TIMEOUT, id, "no outcome for request " + id + " (timer stalled)", e);
        }
    }

    /**
     * Registers {@code request} before it is sent and arms its timeout.
     *
     * @throws IllegalStateException if the node is closed
     */
    PendingRequest register(Message request, LocalShell requester, long timeoutNs) {
        var entry = new PendingRequest(request, requester);
        if (pending.putIfAbsent(entry.id, entry) != null) {
            throw new IllegalArgumentException("request id " + entry.id + " is already waiting for a reply");
        }
        if (requester != null) {
            requester.requestSent();
        }
        try {
            entry.timeout = timer.schedule(() -> onTimeout(entry, timeoutNs), timeoutNs, TimeUnit.NANOSECONDS);
        } catch (RejectedExecutionException e) {
            cancel(entry);
            throw new IllegalStateException("node '" + nodeId + "' is closed; no more requests", e);
        }
        return entry;
    }

    /** Forgets a request that could not be sent. */
    void cancel(PendingRequest entry) {
        if (pending.remove(entry.id, entry)) {
            cancelTimeout(entry);
            if (entry.requester != null) {
                entry.requester.requestSettled();
            }
        }
    }

    /** Runs {@code task} on the table's timer thread after {@code delayNs}; nothing once closed. */
    void schedule(Runnable task, long delayNs) {
        try {
            timer.schedule(task, delayNs, TimeUnit.NANOSECONDS);
        } catch (RejectedExecutionException e) {
            // Closed: the node's components are stopping anyway.
        }
    }

    boolean isPending(MessageId requestId) {
        return pending.containsKey(requestId);
    }

    /**
     * Handles a reply to a request of this node.
     *
     * @return true if the reply was consumed (it completed its request, or it was late and was
     *         dropped); false if it answers no request and must be delivered as a message
     */
    boolean interceptReply(Message reply) {
        MessageId requestId = reply.correlationId();
        Origin origin = reply.origin();
        if (origin != null) {
            PendingRequest waiting = pending.get(requestId);
            if (waiting != null && !mayAnswer.test(waiting.request, origin.nodeId())) {
                // Correlation ids are guessable: only a node the request was routed to answers it.
                long count = foreignReplies.sum();
                foreignReplies.increment();
                if (count < 10 || count % 1000 == 0) {
                    log.warn("node {}: dropped {} from node '{}' (via '{}') to request {} to '{}': that node does not"
                            + " host '{}' here ({} such so far)", nodeId, reply.contents().getClass().getSimpleName(),
                            origin.nodeId(), origin.viaNodeId(), requestId, waiting.request.profile(),
                            waiting.request.profile(), count + 1);
                }
                return true;
            }
        }
        PendingRequest entry = pending.remove(requestId);
        if (entry != null) {
            cancelTimeout(entry);
            record(entry, reply);
            outcomeSink.accept(entry);
            return true;
        }
        boolean late;
        synchronized (timedOut) {
            late = timedOut.contains(requestId);
        }
        if (late) {
            lateReplies.increment();
            log.debug("node {}: dropping late reply {} to request {} (timed out)", nodeId, reply.messageId(), requestId);
            return true;
        }
        if (reply.contents() instanceof RequestFailed failed) {
            // A responder on another node reports a failure on a message that was not a request:
            // there is no future to fail; the responder's node has logged and counted it.
            log.debug("node {}: failure notice for {}, which is no pending request: {}", nodeId, requestId, failed.reason());
            return true;
        }
        return false;
    }

    private static void record(PendingRequest entry, Message reply) {
        switch (reply.contents()) {
            case Undeliverable notice -> entry.failWith(new RequestFailedException(Reason.UNDELIVERABLE, entry.id,
                    "request " + entry.id + " to '" + entry.request.profile() + "' is undeliverable: " + notice.reason()));
            case RequestFailed notice -> entry.failWith(new RequestFailedException(Reason.RESPONDER_FAILED, entry.id,
                    "responder '" + notice.responder() + "' failed handling request " + entry.id + ": " + notice.reason()));
            default -> entry.succeedWith(reply);
        }
    }

    private void onTimeout(PendingRequest entry, long timeoutNs) {
        if (!pending.remove(entry.id, entry)) {
            return;
        }
        timeouts.increment();
        synchronized (timedOut) {
            timedOut.add(entry.id);
            if (timedOut.size() > TIMED_OUT_MEMORY) {
                timedOut.removeFirst();
            }
        }
        entry.failWith(new RequestFailedException(Reason.TIMEOUT, entry.id, "no reply from '" + entry.request.profile()
                + "' to request " + entry.id + " within " + timeoutNs / 1_000_000 + " ms"));
        outcomeSink.accept(entry);
    }

    private static void cancelTimeout(PendingRequest entry) {
        var timeout = entry.timeout;
        if (timeout != null) {
            timeout.cancel(false);
        }
    }

    /** Fails every waiting request with {@code NODE_CLOSED} and stops the timer. */
    void close() {
        timer.shutdownNow();
        for (Map.Entry<MessageId, PendingRequest> item : pending.entrySet()) {
            PendingRequest entry = item.getValue();
            if (pending.remove(item.getKey(), entry)) {
                entry.failWith(closedError(entry.id, nodeId));
                entry.settle();
            }
        }
    }

    static RequestFailedException closedError(MessageId requestId, String nodeId) {
        return new RequestFailedException(Reason.NODE_CLOSED, requestId,
                "node '" + nodeId + "' closed before request " + requestId + " got its reply");
    }

    long timeoutCount() {
        return timeouts.sum();
    }

    long lateReplyCount() {
        return lateReplies.sum();
    }
}
