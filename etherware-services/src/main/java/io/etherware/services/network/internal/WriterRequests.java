package io.etherware.services.network.internal;

import io.etherware.services.network.CloseReason;
import java.util.ArrayDeque;
import java.util.List;

/**
 * What a connection's writer is asked to send besides new messages: acknowledgements,
 * announcements, heartbeats, time probes and replies, messages to send again, and at the end a
 * REJECT and the BYE. Each request is taken once, by {@link #takeRequests} or {@link #takeBye}.
 *
 * <p>Not thread-safe: guarded by the lock of the connection's {@link Link}, with whose work
 * condition a request is signalled.
 */
final class WriterRequests {

    /** Time requests waiting for an answer, at most: a peer flooding them gets some answered. */
    private static final int MAX_TIME_REPLIES = 16;

    private boolean ackRequested;
    private boolean syncRequested;
    private byte[] announce;
    private boolean heartbeatRequested;
    private boolean probeRequested;
    private final ArrayDeque<long[]> timeReplies = new ArrayDeque<>();
    private Frame.Reject reject;
    private Frame.Bye bye;
    private boolean byeTaken;
    private List<InFlight> resend = List.of();
    private int resendIndex;

    boolean hasRequests() {
        return ackRequested || syncRequested || announce != null || heartbeatRequested || probeRequested || !timeReplies.isEmpty()
                || reject != null || resendIndex < resend.size();
    }

    /**
     * Whether something waits that a new message must not overtake: messages of a resumed stream
     * to send again (the peer expects them first), or an announcement (a request sent after a
     * component was added must not reach the peer before the profile its reply goes to).
     */
    boolean mustPrecedeMessages() {
        return announce != null || resendIndex < resend.size();
    }

    /** Ask the peer to acknowledge at once what it has (a SYNC after the turn's messages). */
    void requestSync() {
        syncRequested = true;
    }

    void requestAck() {
        ackRequested = true;
    }

    void requestProbe() {
        probeRequested = true;
    }

    void requestHeartbeat() {
        heartbeatRequested = true;
    }

    /** Answer a time request that left the peer at {@code t1} and arrived here at {@code t2}. */
    void timeReply(long t1, long t2) {
        if (timeReplies.size() < MAX_TIME_REPLIES) {
            timeReplies.addLast(new long[] {t1, t2});
        }
    }

    /** Messages to write again, first, with their numbers: the unacknowledged of a resumed stream. */
    void resend(List<InFlight> entries) {
        resend = entries;
        resendIndex = 0;
    }

    /** The latest announcement replaces one not yet written. */
    void announce(byte[] body) {
        announce = body;
    }

    void reject(Frame.Reject refusal) {
        reject = refusal;
    }

    Frame.Reject pendingReject() {
        return reject;
    }

    /** The first reason given wins. */
    void requestBye(CloseReason reason, String text) {
        if (bye == null) {
            bye = new Frame.Bye(reason.code(), text);
        }
    }

    /** Everything requested so far, and up to {@code batch} messages to send again. */
    WriterTurn takeRequests(int batch) {
        var turn = new WriterTurn();
        turn.ack = ackRequested;
        turn.sync = syncRequested;
        syncRequested = false;
        turn.announce = announce;
        turn.heartbeat = heartbeatRequested;
        turn.probe = probeRequested;
        turn.timeReplies.addAll(timeReplies);
        turn.reject = reject;
        ackRequested = false;
        announce = null;
        heartbeatRequested = false;
        probeRequested = false;
        timeReplies.clear();
        reject = null;
        if (resendIndex < resend.size()) {
            int end = Math.min(resend.size(), resendIndex + batch);
            turn.resend = resend.subList(resendIndex, end);
            resendIndex = end;
        }
        return turn;
    }

    /** The last turn of a closing connection: an acknowledgement, its REJECT and BYE, once; else null. */
    WriterTurn takeBye() {
        if (bye == null || byeTaken) {
            return null;
        }
        byeTaken = true;
        var turn = new WriterTurn();
        turn.ack = true; // what this node's kernel has, so the peer does not report it lost
        turn.reject = reject;
        turn.bye = bye;
        reject = null;
        return turn;
    }
}
