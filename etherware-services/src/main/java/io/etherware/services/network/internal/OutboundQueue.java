package io.etherware.services.network.internal;

import io.etherware.core.message.Criticality;
import java.util.ArrayDeque;
import java.util.List;

/**
 * The messages waiting for one peer: most critical first, first in first out within a level,
 * bounded. When full, the least critical waiting message makes room for a more critical one.
 *
 * <p>Not thread-safe: its {@link Link}'s lock guards it.
 */
final class OutboundQueue {

    private static final int LEVELS = Criticality.values().length;

    /** What {@link #offer} did with an offered message. */
    sealed interface Outcome {
        /** Queued; nothing dropped. */
        Outcome QUEUED = new Queued();

        record Queued() implements Outcome {
        }

        /** Queued, and {@code evicted}, less critical, were dropped to make room. */
        record Evicted(List<Outgoing> evicted) implements Outcome {
        }

        /** Not queued: the queue is full of messages at least as critical. */
        record Full() implements Outcome {
        }
    }

    private final List<ArrayDeque<Outgoing>> levels;
    private final long[] levelBytes = new long[LEVELS];
    private final int capacity;
    private int size;
    private long bytes;

    OutboundQueue(int capacity) {
        this.capacity = capacity;
        var byLevel = new java.util.ArrayList<ArrayDeque<Outgoing>>(LEVELS);
        for (int i = 0; i < LEVELS; i++) {
            byLevel.add(new ArrayDeque<>());
        }
        this.levels = List.copyOf(byLevel);
    }

    /**
     * Queues {@code message} if the queue then holds at most its capacity in messages and
     * {@code maxBytes} in bytes; otherwise evicts the oldest messages of the lowest levels below the
     * message's own to make room, or refuses the message if they would not make enough.
     */
    Outcome offer(Outgoing message, long maxBytes) {
        int level = message.level();
        int length = message.xml().length;
        boolean fits = size < capacity && bytes + length <= maxBytes;
        if (fits) {
            add(message);
            return Outcome.QUEUED;
        }
        long evictableBytes = 0;
        int evictable = 0;
        for (int lower = 0; lower < level; lower++) {
            evictableBytes += levelBytes[lower];
            evictable += levels.get(lower).size();
        }
        long bytesNeeded = bytes + length - maxBytes;
        if (evictable == 0 || evictableBytes < bytesNeeded || length > maxBytes) {
            return new Outcome.Full();
        }
        var evicted = new java.util.ArrayList<Outgoing>();
        for (int lower = 0; lower < level; lower++) {
            ArrayDeque<Outgoing> queue = levels.get(lower);
            while (!queue.isEmpty() && (size >= capacity || bytes + length > maxBytes)) {
                Outgoing victim = queue.pollFirst();
                size--;
                bytes -= victim.xml().length;
                levelBytes[lower] -= victim.xml().length;
                evicted.add(victim);
            }
        }
        add(message);
        return new Outcome.Evicted(List.copyOf(evicted));
    }

    private void add(Outgoing message) {
        levels.get(message.level()).addLast(message);
        size++;
        bytes += message.xml().length;
        levelBytes[message.level()] += message.xml().length;
    }

    /** The most critical, oldest message, left in the queue, or null. */
    Outgoing peek() {
        for (int level = levels.size() - 1; level >= 0; level--) {
            Outgoing message = levels.get(level).peekFirst();
            if (message != null) {
                return message;
            }
        }
        return null;
    }

    /** The most critical, oldest message, or null. */
    Outgoing poll() {
        for (int level = levels.size() - 1; level >= 0; level--) {
            Outgoing message = levels.get(level).pollFirst();
            if (message != null) {
                size--;
                bytes -= message.xml().length;
                levelBytes[level] -= message.xml().length;
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
            bytes += message.xml().length;
            levelBytes[message.level()] += message.xml().length;
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

    /** Bytes of the encoded messages waiting. */
    long bytes() {
        return bytes;
    }

    boolean isEmpty() {
        return size == 0;
    }
}
