package io.etherware.services.network.internal;

import io.etherware.core.kernel.Kernel;
import io.etherware.core.kernel.RequestFailed;
import io.etherware.core.kernel.Undeliverable;
import io.etherware.core.message.Criticality;
import io.etherware.core.message.Message;
import java.util.List;
import java.util.concurrent.atomic.AtomicLong;
import org.slf4j.Logger;
import org.slf4j.LoggerFactory;

/**
 * What the messenger does with a message it cannot deliver: counts it and tells whoever waits for
 * it (the sender of a message; for a reply, the requester), or sheds it (NONE, LOW from a full
 * queue), so that no request hangs until its timeout for a loss the messenger knows of.
 *
 * <p>Thread-safety: any thread; never called with a link's lock held (it sends through the kernel).
 */
final class Losses {

    private static final Logger log = LoggerFactory.getLogger("io.etherware.services.network.NetworkMessenger");

    private final Kernel kernel;
    private final Counters counters;
    private final AtomicLong overflowLogged = new AtomicLong();

    Losses(Kernel kernel, Counters counters) {
        this.kernel = kernel;
        this.counters = counters;
    }

    /**
     * A message that cannot be delivered: counted, and its sender gets an {@link Undeliverable}
     * notice (a request of the sender's then fails); without a sender, a log line.
     */
    void lost(Message message, String reason) {
        counters.undeliverable.increment();
        if (message.isReply() && !(message.contents() instanceof Undeliverable)
                && !(message.contents() instanceof RequestFailed)) {
            failRequestOf(message, reason);
            return;
        }
        if (message.sender() == null || message.contents() instanceof Undeliverable
                || message.contents() instanceof RequestFailed) {
            log.warn("node {}: message {} to '{}' is lost: {}", kernel.nodeId(), message.messageId(), message.profile(), reason);
            return;
        }
        log.debug("node {}: message {} to '{}' is undeliverable: {}", kernel.nodeId(), message.messageId(), message.profile(),
                reason);
        try {
            kernel.send(new Message(message.sender(), kernel.profile(), kernel.clock().epochNanos(), message.qos(),
                    new Undeliverable(message.profile().toString(), message.messageId().toString(), reason),
                    kernel.newMessageId(), message.messageId()));
        } catch (RuntimeException e) {
            log.warn("node {}: could not tell '{}' that message {} is lost ({}): {}", kernel.nodeId(), message.sender(),
                    message.messageId(), reason, e.toString());
        }
    }

    /**
     * A reply that cannot be delivered: its requester, not its responder, must hear of it, or the
     * request hangs until its timeout. The requester's node gets a {@link RequestFailed} for the
     * request (queued for that node like any message; if it cannot go either, a log line).
     */
    private void failRequestOf(Message reply, String reason) {
        String responder = reply.sender() == null ? kernel.nodeId() : reply.sender().toString();
        log.debug("node {}: reply {} to request {} is lost ({}); failing the request at its requester", kernel.nodeId(),
                reply.messageId(), reply.correlationId(), reason);
        try {
            kernel.send(new Message(reply.profile(), reply.sender(), kernel.clock().epochNanos(), reply.qos(),
                    new RequestFailed(reply.correlationId().toString(), responder, "its reply was lost: " + reason),
                    kernel.newMessageId(), reply.correlationId()));
        } catch (RuntimeException e) {
            log.warn("node {}: could not tell the requester of {} that its reply is lost ({}): {}", kernel.nodeId(),
                    reply.correlationId(), reason, e.toString());
        }
    }

    /** Reports messages written to a peer whose fate is unknown. */
    void reportLost(List<InFlight> entries, String reason) {
        for (InFlight entry : entries) {
            lost(entry.outgoing().message(), reason);
        }
    }

    /** A message dropped from a full queue: NONE and LOW are shed (counted); others are reported. */
    void dropped(Message message, String peerId, String reason) {
        if (message.qos().criticality().compareTo(Criticality.LOW) > 0) {
            lost(message, reason);
            return;
        }
        counters.overflowDropped.increment();
        long count = overflowLogged.incrementAndGet();
        if (count == 1 || count % 10_000 == 0) {
            log.warn("node {}: shedding {} messages to node '{}' ({} so far): {}", kernel.nodeId(),
                    message.qos().criticality(), peerId, count, reason);
        }
    }
}
