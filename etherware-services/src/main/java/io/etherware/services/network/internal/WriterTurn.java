package io.etherware.services.network.internal;

import java.util.ArrayList;
import java.util.List;

/**
 * What a connection's writer does in one turn, taken under the link's lock and then written
 * without it.
 *
 * <p>Not thread-safe: made by the writer for itself.
 */
final class WriterTurn {

    boolean ack;
    byte[] announce;
    boolean heartbeat;
    /** Ask the peer to acknowledge at once, after this turn's messages. */
    boolean sync;
    boolean probe;
    /** Time requests to answer: each {t1, t2}. */
    final List<long[]> timeReplies = new ArrayList<>(2);
    Frame.Reject reject;
    /** Set on the last turn: say why and stop. */
    Frame.Bye bye;
    List<InFlight> resend = List.of();
    final List<Outgoing> fresh = new ArrayList<>();

    boolean isLast() {
        return bye != null;
    }
}
