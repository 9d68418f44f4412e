package io.etherware.services.notifier;

import io.etherware.core.component.Component;
import io.etherware.core.component.ComponentContext;
import io.etherware.core.kernel.RequestFailed;
import io.etherware.core.kernel.Undeliverable;
import io.etherware.core.message.Contents;
import io.etherware.core.message.Message;
import java.util.concurrent.atomic.AtomicBoolean;

/**
 * The Notifier as a component: subscribe, unsubscribe and retarget by message, answered with a
 * {@link NotifierReply} when the request has a sender. Bad requests are refused in the reply,
 * naming the field; they never fail the component (it has no state to restart).
 *
 * <p>Threading: called by the kernel one message at a time on a dispatcher thread; does not
 * block beyond {@link Notifier#unsubscribe}'s wait for one in-flight send.
 */
final class NotifierComponent implements Component {

    private final Notifier notifier;
    private final AtomicBoolean unknownLogged = new AtomicBoolean();

    NotifierComponent(Notifier notifier) {
        this.notifier = notifier;
    }

    @Override
    public void onStart(ComponentContext context) {
        notifier.start();
    }

    @Override
    public void onMessage(Message message, ComponentContext context) {
        Contents contents = message.contents();
        switch (contents) {
            case TickSubscribe subscribe -> answer(message, context, subscribe(subscribe, message));
            case TickUnsubscribe unsubscribe -> answer(message, context, unsubscribe(unsubscribe));
            case TickRetarget retarget -> answer(message, context, retarget(retarget));
            case Undeliverable notice -> {
                notifier.countUndeliverableNotice();
                context.logger().debug("a Tick was not delivered: {}", notice);
            }
            case RequestFailed ignored -> {
                // Not expected: the Notifier makes no requests.
            }
            default -> {
                if (unknownLogged.compareAndSet(false, true)) {
                    context.logger().warn("ignoring message {} from '{}' with contents {}: the Notifier understands"
                            + " TickSubscribe, TickUnsubscribe and TickRetarget (logged once)", message.messageId(),
                            message.sender(), contents.getClass().getSimpleName());
                }
                answer(message, context, NotifierReply.refused(null, "unsupported contents "
                        + contents.getClass().getSimpleName() + "; send TickSubscribe, TickUnsubscribe or TickRetarget"));
            }
        }
    }

    private NotifierReply subscribe(TickSubscribe request, Message message) {
        Subscription subscription;
        try {
            subscription = request.toSubscription(message.sender());
        } catch (IllegalArgumentException | NullPointerException e) {
            return NotifierReply.refused(request.name(), e.getMessage());
        }
        try {
            Subscription added = notifier.subscribe(subscription);
            return NotifierReply.accepted(added.name(), added.firstReleaseNs());
        } catch (IllegalArgumentException | IllegalStateException e) {
            return NotifierReply.refused(subscription.name(), e.getMessage());
        }
    }

    private NotifierReply unsubscribe(TickUnsubscribe request) {
        if (request.name() == null) {
            return NotifierReply.refused(null, "name=null: name the subscription to remove");
        }
        return notifier.unsubscribe(request.name()).isPresent() ? NotifierReply.accepted(request.name(), null)
                : NotifierReply.refused(request.name(), "no subscription named '" + request.name() + "'");
    }

    private NotifierReply retarget(TickRetarget request) {
        if (request.name() == null || request.target() == null) {
            return NotifierReply.refused(request.name(), "name=" + request.name() + ", target=" + request.target()
                    + ": both are required");
        }
        try {
            notifier.retarget(request.name(), request.target());
            return NotifierReply.accepted(request.name(), null);
        } catch (IllegalArgumentException e) {
            return NotifierReply.refused(request.name(), e.getMessage());
        }
    }

    private static void answer(Message request, ComponentContext context, NotifierReply reply) {
        if (request.hasSender() && !request.isReply()) {
            context.reply(request, reply);
        }
    }
}
