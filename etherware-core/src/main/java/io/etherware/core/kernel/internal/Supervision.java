package io.etherware.core.kernel.internal;

import io.etherware.core.kernel.Escalation;
import io.etherware.core.kernel.Kernel;
import io.etherware.core.kernel.RequestFailed;
import io.etherware.core.kernel.Undeliverable;
import io.etherware.core.message.Contents;
import io.etherware.core.message.Message;
import io.etherware.core.message.MessageId;
import io.etherware.core.message.Profile;
import io.etherware.core.time.NodeClock;
import java.util.concurrent.atomic.LongAdder;
import java.util.function.Consumer;
import java.util.function.Supplier;
import org.slf4j.Logger;
import org.slf4j.LoggerFactory;

/**
 * The node's side of supervision (the root of the Management Tree): reports a component's failure
 * (logged, and a {@link RequestFailed} notice to the sender of a request) and applies the node's
 * {@link Escalation} when a component exceeds its restart intensity. The restart policy of each
 * component is applied by its shell, on its owner thread (see {@link LocalShell}).
 *
 * <p>Owned by {@link KernelCore}.
 *
 * <p>Thread-safety: called on the thread that owns the failing component's gate; takes no lock
 * (the reset of every component runs later, at each one's own boundary).
 */
final class Supervision {

    /** Logs as the kernel: these are the kernel's messages. */
    private static final Logger log = LoggerFactory.getLogger(Kernel.class);

    private final String nodeId;
    private final NodeClock clock;
    private final Escalation escalation;
    private final RequestTable requests;
    private final ShellTable shells;
    /** The kernel's send, for failure notices. */
    private final Consumer<Message> send;
    private final Supplier<MessageId> newMessageId;
    /** Closes the node on another thread (the STOP_NODE escalation). */
    private final Runnable closeNode;
    private final LongAdder escalations = new LongAdder();
    private final LongAdder resets = new LongAdder();

    /**
     * @param requests tells whether a failed message is a pending request of this node
     * @param shells   the components a RESET_ALL escalation resets
     */
    Supervision(String nodeId, NodeClock clock, Escalation escalation, RequestTable requests, ShellTable shells,
                Consumer<Message> send, Supplier<MessageId> newMessageId, Runnable closeNode) {
        this.nodeId = nodeId;
        this.clock = clock;
        this.escalation = escalation;
        this.requests = requests;
        this.shells = shells;
        this.send = send;
        this.newMessageId = newMessageId;
        this.closeNode = closeNode;
    }

    /**
     * Logs the failure of component {@code component} and, if the message was a request, fails it
     * (owner thread).
     */
    void reportFailure(Profile component, Message message, Throwable failure, long failures) {
        String name = component.toString();
        log.warn("node {}: component '{}' failed handling message {} from '{}' (failure {})", nodeId, name,
                message.messageId(), message.sender(), failures, failure);
        Contents contents = message.contents();
        if (message.sender() == null || contents instanceof Undeliverable || contents instanceof RequestFailed) {
            return;
        }
        // A local request is known; a message from another node may be a request there, whose
        // kernel drops the notice if it is not.
        if (requests.isPending(message.messageId()) || !nodeId.equals(message.messageId().nodeId())) {
            send.accept(new Message(message.sender(), component, clock.epochNanos(), message.qos(),
                    new RequestFailed(message.messageId().toString(), name, failure.toString()),
                    newMessageId.get(), message.messageId()));
        }
    }

    /** Component {@code component} exceeded its restart intensity: apply the node's policy (owner thread). */
    void escalate(Profile component, Throwable failure) {
        escalations.increment();
        switch (escalation) {
            case RESET_ALL -> {
                resets.increment();
                log.error("node {}: escalation from '{}' ({}): resetting all {} components", nodeId, component,
                        failure.toString(), shells.registered().size());
                for (LocalShell each : shells.registered()) {
                    each.atBoundary(each::reset);
                }
            }
            case STOP_NODE -> {
                log.error("node {}: escalation from '{}' ({}): stopping the node", nodeId, component,
                        failure.toString());
                closeNode.run();
            }
        }
    }

    long escalationCount() {
        return escalations.sum();
    }

    long resetCount() {
        return resets.sum();
    }
}
