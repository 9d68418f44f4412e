package io.etherware.services.network.internal;

import java.util.List;

/**
 * A lane's messages waiting for its writer, most critical first ({@link OutboundQueue}), and what
 * a writer's turn takes of them: within the room the window leaves, the bound on NONE and LOW bytes
 * in flight on one lane ({@link OutboundStream#lowRoomFor}) and the NONE ordering across lanes
 * ({@link LaneOrder}). A message that leaves it for good without being written is settled in the
 * lane's order.
 *
 * <p>Locking: guarded by its link's lock, with which the link shares it, its order and its
 * outbound stream; every method is called with that lock held. Takes no lock.
 */
final class Outbox {

    private final OutboundQueue queue;
    private final LaneOrder order;
    /** The lane's stream to the peer: what is in flight bounds what may be queued and taken. */
    private final OutboundStream out;
    /** The queue's size, readable without the lock as a hint. */
    private volatile int queuedHint;

    Outbox(int capacity, LaneOrder order, OutboundStream out) {
        this.queue = new OutboundQueue(capacity);
        this.order = order;
        this.out = out;
    }

    boolean isEmpty() {
        return queue.isEmpty();
    }

    int size() {
        return queue.size();
    }

    /** The message a writer would take next, left in the queue, or null. */
    Outgoing peek() {
        return queue.peek();
    }

    /**
     * Whether a sender may write {@code outgoing} itself on {@code direct}, the idle active
     * connection: nothing waits or must go first, the window and the bytes in flight
     * ({@code maxBytes}) have room, so do the LOW bound and the lane order, and the socket's buffer
     * takes the frame without blocking (see {@link ConnectionOutput#fitsDirectWrite}).
     */
    boolean mayGoDirectly(Outgoing outgoing, Connection direct, int window, long maxBytes) {
        int length = outgoing.xml().length;
        return queue.isEmpty() && !direct.requests.mustPrecedeMessages() && out.size() < window
                && out.bytes() + length <= maxBytes && out.lowRoomFor(outgoing, 0) && order.mayGo(outgoing)
                && direct.output().fitsDirectWrite(length + Frame.DATA_OVERHEAD_BYTES);
    }

    /**
     * Queues {@code outgoing} if the queue and the messages in flight then hold at most
     * {@code maxBytes}, evicting less critical messages to make room (see
     * {@link OutboundQueue#offer}); what is evicted, or {@code outgoing} itself when it does not
     * fit, is settled here and left to the caller to report.
     */
    OutboundQueue.Outcome offer(Outgoing outgoing, long maxBytes) {
        OutboundQueue.Outcome outcome = queue.offer(outgoing, maxBytes - out.bytes());
        queuedHint = queue.size();
        switch (outcome) {
            case OutboundQueue.Outcome.Evicted evicted -> evicted.evicted().forEach(order::settle);
            case OutboundQueue.Outcome.Full full -> order.settle(outgoing);
            default -> { }
        }
        return outcome;
    }

    /**
     * Takes up to {@code room} new messages for {@code turn}, most critical first, stopping at one
     * that must wait (for LOW room or for lane 0), and marks the turn to end with a SYNC when it
     * carries messages a NONE message of lane 1 waits for.
     */
    void fill(WriterTurn turn, int room) {
        long lowChosen = 0;
        while (turn.fresh.size() < room) {
            Outgoing next = queue.peek();
            if (next == null || !out.lowRoomFor(next, lowChosen) || !order.mayGo(next)) {
                break; // the rest are NONE or LOW too: they wait for acknowledgements
            }
            if (next.isSheddable()) {
                lowChosen += next.xml().length;
            }
            turn.fresh.add(queue.poll());
        }
        queuedHint = queue.size();
        if (order.syncAfter(!turn.fresh.isEmpty() || !turn.resend.isEmpty())) {
            turn.sync = true; // more of what the NONE message waits for goes out now
        }
    }

    /** Puts messages a writer took and could not number back at the front, in their order. */
    void pushBack(List<Outgoing> taken) {
        queue.pushBack(taken);
        queuedHint = queue.size();
    }

    /** Removes and returns every waiting message, most critical first, settling each. */
    List<Outgoing> abandon() {
        List<Outgoing> waited = queue.drain();
        waited.forEach(order::settle);
        queuedHint = 0;
        return waited;
    }
}
