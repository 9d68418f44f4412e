package io.etherware.examples.bench;

import com.sun.management.GarbageCollectionNotificationInfo;
import java.lang.management.GarbageCollectorMXBean;
import java.lang.management.ManagementFactory;
import java.util.ArrayList;
import java.util.List;
import java.util.Locale;
import java.util.Map;
import java.util.TreeMap;
import javax.management.ListenerNotFoundException;
import javax.management.Notification;
import javax.management.NotificationEmitter;
import javax.management.NotificationListener;
import javax.management.openmbean.CompositeData;

/**
 * The garbage collector's pauses during a run, from the JVM's GC notifications: per collector,
 * how many and the longest, in milliseconds as the JVM reports them. Only collectors that pause
 * the application are counted: G1's and ZGC's concurrent cycles ({@code G1 Concurrent GC},
 * {@code ZGC ... Cycles}) run beside it and are listed apart.
 *
 * <p>Notifications arrive on a JMX thread; {@link #summary()} may be called from any thread.
 */
final class CollectorPauses implements AutoCloseable {

    private final Map<String, long[]> byCollector = new TreeMap<>(); // name -> {count, maxMs, totalMs}
    private final List<NotificationEmitter> emitters = new ArrayList<>();
    private final NotificationListener listener = this::onNotification;

    private CollectorPauses() {
    }

    /** Starts listening to every collector. */
    static CollectorPauses start() {
        var pauses = new CollectorPauses();
        for (GarbageCollectorMXBean bean : ManagementFactory.getGarbageCollectorMXBeans()) {
            if (bean instanceof NotificationEmitter emitter) {
                emitter.addNotificationListener(pauses.listener, null, null);
                pauses.emitters.add(emitter);
            }
        }
        return pauses;
    }

    private void onNotification(Notification notification, Object handback) {
        if (!GarbageCollectionNotificationInfo.GARBAGE_COLLECTION_NOTIFICATION.equals(notification.getType())) {
            return;
        }
        var info = GarbageCollectionNotificationInfo.from((CompositeData) notification.getUserData());
        long durationMs = info.getGcInfo().getDuration();
        synchronized (byCollector) {
            long[] counts = byCollector.computeIfAbsent(info.getGcName(), name -> new long[3]);
            counts[0]++;
            counts[1] = Math.max(counts[1], durationMs);
            counts[2] += durationMs;
        }
    }

    /** Whether a collector of this name pauses the application (not a concurrent cycle). */
    static boolean isPause(String collectorName) {
        return !collectorName.contains("Concurrent") && !collectorName.contains("Cycles");
    }

    /** What was seen so far. */
    Summary summary() {
        var collectors = new ArrayList<Collector>();
        synchronized (byCollector) {
            byCollector.forEach((name, counts) -> collectors.add(
                    new Collector(name, isPause(name), counts[0], counts[1], counts[2])));
        }
        return new Summary(collectors);
    }

    @Override
    public void close() {
        for (NotificationEmitter emitter : emitters) {
            try {
                emitter.removeNotificationListener(listener);
            } catch (ListenerNotFoundException e) {
                // Already gone.
            }
        }
    }

    /**
     * One collector's events.
     *
     * @param name    the collector's MXBean name
     * @param pause   whether its events pause the application
     * @param count   events
     * @param maxMs   the longest, ms (JVM resolution: whole milliseconds)
     * @param totalMs their sum, ms
     */
    public record Collector(String name, boolean pause, long count, long maxMs, long totalMs) {
    }

    /**
     * Every collector's events during a run.
     *
     * @param collectors per collector, by name
     */
    public record Summary(List<Collector> collectors) {

        /** Copies the list. */
        public Summary {
            collectors = List.copyOf(collectors);
        }

        /** Pauses over every pausing collector. */
        public long pauseCount() {
            return collectors.stream().filter(Collector::pause).mapToLong(Collector::count).sum();
        }

        /** The longest pause, ms. */
        public long maxPauseMs() {
            return collectors.stream().filter(Collector::pause).mapToLong(Collector::maxMs).max().orElse(0);
        }

        /** A markdown table, one line per collector. */
        String markdown() {
            var text = new StringBuilder("| collector | kind | events | max ms | total ms |\n|---|---|--:|--:|--:|\n");
            for (Collector c : collectors) {
                text.append(String.format(Locale.ROOT, "| %s | %s | %d | %d | %d |%n", c.name(),
                        c.pause() ? "pause" : "concurrent", c.count(), c.maxMs(), c.totalMs()));
            }
            if (collectors.isEmpty()) {
                text.append("| (none) | | 0 | 0 | 0 |\n");
            }
            return text.toString();
        }
    }
}
