package io.etherware.core.component;

import io.etherware.core.message.Message;

/**
 * The logic of a component: what a user writes (the Strategy of the paper's component model,
 * Section III-B). The kernel wraps it in a {@link Shell} and calls it one message at a time.
 *
 * <p>Only {@link #onMessage} is required, so a stateless component can be a lambda:
 * {@code (message, context) -> context.reply(message, Empty.INSTANCE)}. A stateful component
 * implements {@link #snapshot()} and {@link #restore(ComponentState)} (the Memento), which the
 * kernel uses to restart it after a failure, to upgrade it and, later, to migrate it.
 *
 * <p>Threading contract: the kernel never calls two methods of one instance at the same time,
 * and every call happens-after the previous one, so the instance needs no synchronization of
 * its own. The calls may come from different threads over time. {@link #onMessage} runs on a
 * dispatcher thread and must not block: a blocked handler delays every component that shares
 * the dispatcher.
 */
@FunctionalInterface
public interface Component {

    /**
     * Called once before the first message, with the context to keep for later use. Runs on the
     * thread that starts the component (the node's {@code start()} caller, the caller of a
     * runtime add, or the dispatcher that restarts the component after a failure).
     *
     * @param context what the component may do; valid for the component's whole life, from any
     *                thread
     * @throws Exception to refuse to start; the component then goes to
     *                   {@link Shell.State#FAILED}
     */
    default void onStart(ComponentContext context) throws Exception {
    }

    /**
     * Handles one message. Called on a dispatcher thread; must not block.
     *
     * @param message the message, addressed to this component's profile (or a query it matched)
     * @param context the same context {@link #onStart} received
     * @throws Exception any failure; it goes to the kernel's supervision (restart policy),
     *                   never to the dispatcher
     */
    void onMessage(Message message, ComponentContext context) throws Exception;

    /**
     * Called once when the component stops: removed, restarted, replaced by an upgrade, or the
     * node closes. Release resources here; an exception is logged and otherwise ignored.
     */
    default void onStop() {
    }

    /**
     * The component's state now, at a message boundary, or null for a component without state.
     * With the default restart policy the kernel calls this after every message it handled
     * successfully, so it must be cheap: return an immutable record, do not copy large arrays.
     *
     * @return the state, a record registered as contents; null for none (the default)
     */
    default ComponentState snapshot() {
        return null;
    }

    /**
     * Takes over {@code state} before {@link #onStart}: a restart from the last snapshot, or an
     * upgrade handing over the previous version's state (check
     * {@link ComponentState#schemaVersion()} to convert old state).
     *
     * @param state a state this component type's {@link #snapshot()} returned, possibly from an
     *              older version of it; never null (a null snapshot is not restored)
     * @throws Exception if the state cannot be used; an upgrade is then rolled back
     */
    default void restore(ComponentState state) throws Exception {
    }
}
