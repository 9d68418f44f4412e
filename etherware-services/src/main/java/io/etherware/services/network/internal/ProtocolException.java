package io.etherware.services.network.internal;

import io.etherware.services.network.CloseReason;
import java.io.IOException;

/** A peer broke the protocol; the connection closes for {@link #reason()}. */
class ProtocolException extends IOException {

    private final CloseReason reason;

    ProtocolException(CloseReason reason, String message) {
        super(message);
        this.reason = reason;
    }

    ProtocolException(CloseReason reason, String message, Throwable cause) {
        super(message, cause);
        this.reason = reason;
    }

    CloseReason reason() {
        return reason;
    }
}
