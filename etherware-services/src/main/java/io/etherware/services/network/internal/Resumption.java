package io.etherware.services.network.internal;

import io.etherware.services.network.CloseReason;
import java.util.List;

/**
 * How a lane's two streams carry on over a new connection (NETWORK-PROTOCOL.md, "Streams" and the
 * one-connection rule under "Connection"): whether the candidate replaces the connection in use,
 * and, from the peer's RESUME, what of this node's stream is released, sent again or of unknown
 * fate, and from where the peer's stream goes on.
 *
 * <p>Locking: shares its link's streams; {@link #resume} is called holding the inbound stream's
 * monitor and then the link's lock, as the link guards them. Takes no lock.
 */
final class Resumption {

    /** This node's stream to the peer on the lane. */
    private final OutboundStream out;
    /** The peer's stream to this node on the lane. */
    private final InboundStream inbound;

    Resumption(OutboundStream out, InboundStream inbound) {
        this.out = out;
        this.inbound = inbound;
    }

    /**
     * Resumes or restarts both streams for {@code candidate}, handshaken, unless {@code current},
     * the connection in use (or null), wins the one-connection rule; a loser in use is asked to say
     * BYE. A peer claiming more of our stream than was sent is refused, and our stream starts
     * afresh. The link makes an accepted candidate its connection.
     */
    LaneActivation resume(Connection current, Connection candidate, Frame.Resume theirs) {
        Connection loser = null;
        if (current != null && current != candidate) {
            if (!candidate.isPreferredOver(current)) {
                return new LaneActivation(false, candidate, List.of(), null);
            }
            loser = current;
        }
        List<InFlight> lost = List.of();
        if (theirs.knownStreamId() == out.streamId()) {
            // A RESUME that contradicts the stream: a restart raced a second connection, or
            // a connection in the peer's name acknowledged what it now denies (an impostor,
            // or a bug).
            String refusal = out.resumeRefusal(theirs.receivedCount());
            if (refusal != null) {
                // With a connection in use, the candidate is the one that lies (an
                // impostor, on a plain link): refuse it and leave the stream alone.
                // Without one, start the stream afresh so the next connection agrees.
                List<InFlight> unknown = current != null && current != candidate ? List.of() : out.reset();
                return new LaneActivation(false, candidate, unknown, refusal);
            }
            out.acknowledge(theirs.receivedCount());
            candidate.requests.resend(out.unacknowledged());
        } else {
            // The peer does not know our stream: what it did not acknowledge is of unknown
            // fate; the peer starts our stream from 0 (it adopts its id from our RESUME).
            lost = out.restartNumbering();
            candidate.requests.resend(List.of());
        }
        inbound.resume(theirs.streamId());
        if (loser != null) {
            loser.requests.requestBye(CloseReason.DUPLICATE, "replaced by the connection dialed by '"
                    + candidate.initiatorId() + "'");
        }
        return new LaneActivation(true, loser, lost, null);
    }
}
