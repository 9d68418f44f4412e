package io.etherware.core.kernel.internal;

import io.etherware.core.component.ComponentContext;
import io.etherware.core.message.Contents;
import io.etherware.core.message.Message;
import io.etherware.core.message.MessageId;
import io.etherware.core.message.Profile;
import io.etherware.core.message.QoS;
import io.etherware.core.time.NodeClock;
import java.util.Objects;
import java.util.concurrent.CompletableFuture;
import org.slf4j.Logger;
import org.slf4j.LoggerFactory;

/**
 * The {@link ComponentContext} of one component: builds messages with the component as sender and
 * hands them to the kernel.
 *
 * <p>Thread-safety: immutable; every method may be called from any thread (the blocking request
 * refuses dispatcher threads).
 */
final class ShellContext implements ComponentContext {

    private final KernelCore kernel;
    private final LocalShell shell;
    private final Profile self;
    private final Logger logger;

    ShellContext(KernelCore kernel, LocalShell shell) {
        this.kernel = kernel;
        this.shell = shell;
        this.self = shell.profile();
        this.logger = LoggerFactory.getLogger("etherware.component." + shell.name());
    }

    @Override
    public Profile self() {
        return self;
    }

    @Override
    public NodeClock clock() {
        return kernel.clock();
    }

    @Override
    public Logger logger() {
        return logger;
    }

    @Override
    public MessageId send(Profile to, Contents contents, QoS qos) {
        Message message = message(to, contents, qos, null);
        kernel.send(message);
        return message.messageId();
    }

    @Override
    public MessageId reply(Message request, Contents contents) {
        Objects.requireNonNull(request, "request");
        if (!request.hasSender()) {
            throw new IllegalArgumentException("message " + request.messageId() + " has no sender to reply to");
        }
        Message reply = message(request.sender(), contents, request.qos(), request.messageId());
        kernel.send(reply);
        return reply.messageId();
    }

    @Override
    public CompletableFuture<Message> request(Profile to, Contents contents) {
        return request(to, contents, QoS.NONE, kernel.config().defaultRequestTimeoutNs());
    }

    @Override
    public CompletableFuture<Message> request(Profile to, Contents contents, QoS qos, long timeoutNs) {
        return kernel.request(message(to, contents, qos, null), shell, timeoutNs);
    }

    @Override
    public Message requestBlocking(Profile to, Contents contents, QoS qos, long timeoutNs) {
        return kernel.requestBlocking(message(to, contents, qos, null), timeoutNs);
    }

    private Message message(Profile to, Contents contents, QoS qos, MessageId correlationId) {
        return new Message(to, self, kernel.clock().epochNanos(), qos, contents, kernel.newMessageId(), correlationId);
    }
}
