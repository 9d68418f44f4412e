package io.etherware.services.notifier;

import io.etherware.core.message.ContentsTypes;

/** Registers the Notifier's message contents under their wire names. Thread-safe (idempotent). */
final class NotifierContents {

    private NotifierContents() {
    }

    static void register(ContentsTypes types) {
        types.register("notifier.subscribe", TickSubscribe.class);
        types.register("notifier.unsubscribe", TickUnsubscribe.class);
        types.register("notifier.retarget", TickRetarget.class);
        types.register("notifier.reply", NotifierReply.class);
    }
}
