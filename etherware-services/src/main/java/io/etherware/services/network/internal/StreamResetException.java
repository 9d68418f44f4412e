package io.etherware.services.network.internal;

import io.etherware.services.network.CloseReason;
import java.util.List;

/**
 * A peer's acknowledgement contradicted the stream, which was started afresh: the connection
 * closes ({@code SEQUENCE_ERROR}) and {@link #lost}, of unknown fate, are reported to their senders.
 */
final class StreamResetException extends ProtocolException {
    final transient List<InFlight> lost;

    StreamResetException(String message, List<InFlight> lost) {
        super(CloseReason.SEQUENCE_ERROR, message);
        this.lost = lost;
    }
}
