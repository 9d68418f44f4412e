package io.etherware.services.network.internal;

import io.etherware.core.message.Criticality;
import java.util.ArrayDeque;
import java.util.List;

/**
 * The messages waiting for one peer: most critical first, first in first out within a level,
 * bounded. When full, the least critical waiting message makes room for a more critical one.
 *
 * <p>Not thread-safe: the {@link Peer}'s lock guards it.
 */
final class OutboundQueue {

    private static final int LEVELS = Criticality.values().length;

    /** What {@link #offer} did with an offered message. */
    sealed interface Outcome {
        /** Queued; nothing dropped. */
        Outcome QUEUED = new Queued();

        record Queued() implements Outcome {
        }

        /** Queued, and {@code evicted}, less critical, was dropped to make room. */
        record Evicted(Outgoing evicted) implements Outcome {
        }

        /** Not queued: the queue is full of messages at least as critical. */
        record Full() implements Outcome {
        }
    }

    private final List<ArrayDeque<Outgoing>> levels;
    private final int capacity;
    private int size;

    OutboundQueue(int capacity) {
        this.capacity = capacity;
        var byLevel = new java.util.ArrayList<ArrayDeque<Outgoing>>(LEVELS);
        for (int i = 0; i < LEVELS; i++) {
            byLevel.add(new ArrayDeque<>());
        }
        this.levels = List.copyOf(byLevel);
    }

    /**
     * Queues {@code message}; when full, evicts the oldest message of the lowest level below the
     * message's own, or refuses the message if there is none.
     */
    Outcome offer(Outgoing message) {
        int level = message.level();
        if (size < capacity) {
            levels.get(level).addLast(message);
            size++;
            return Outcome.QUEUED;
        }
        for (int lower = 0; lower < level; lower++) {
            if (!levels.get(lower).isEmpty()) {
                Outgoing evicted = levels.get(lower).pollFirst();
                levels.get(level).addLast(message);
                return new Outcome.Evicted(evicted);
            }
        }
        return new Outcome.Full();
    }

    /** The most critical, oldest message, or null. */
    Outgoing poll() {
        for (int level = levels.size() - 1; level >= 0; level--) {
            Outgoing message = levels.get(level).pollFirst();
            if (message != null) {
                size--;
                return message;
            }
        }
        return null;
    }

    /** Puts back messages taken by {@link #poll} and not sent, ahead of the rest, in their order. */
    void pushBack(List<Outgoing> taken) {
        for (Outgoing message : taken.reversed()) {
            levels.get(message.level()).addFirst(message);
            size++;
        }
    }

    /** Removes and returns everything, most critical first. */
    List<Outgoing> drain() {
        var all = new java.util.ArrayList<Outgoing>(size);
        Outgoing message;
        while ((message = poll()) != null) {
            all.add(message);
        }
        return all;
    }

    int size() {
        return size;
    }

    boolean isEmpty() {
        return size == 0;
    }
}
