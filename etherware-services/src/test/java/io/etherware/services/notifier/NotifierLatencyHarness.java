package io.etherware.services.notifier;

import io.etherware.core.component.Component;
import io.etherware.core.kernel.EtherwareNode;
import io.etherware.core.message.Criticality;
import io.etherware.core.message.Profile;
import io.etherware.rt.platform.ThreadPolicy;
import io.etherware.rt.scheduling.RealtimeScheduler;
import java.io.BufferedReader;
import java.io.IOException;
import java.io.InputStreamReader;
import java.nio.charset.StandardCharsets;
import java.util.ArrayList;
import java.util.List;
import java.util.Locale;
import java.util.concurrent.TimeUnit;
import org.HdrHistogram.Histogram;

/**
 * Notifier lateness (send time minus scheduled release) at 1 kHz, without and with the spin
 * option, beside {@code cyclictest} (rt-tests) at the same period and priority when installed.
 * Not part of the test suite: a main, run with {@code java -cp} (command in the module's report).
 *
 * <p>The Notifier runs on a node with the real-time scheduler (Table II); its Ticks go to a HIGH
 * component that does nothing. Only the Notifier thread is real-time; the JVM is not run under
 * {@code chrt}. The spin, when on, is bounded by the Notifier's configuration (at most 100 µs per
 * release).
 *
 * <p>A release the Notifier skipped for lateness (half a period, 500 µs) is counted in the
 * percentiles as 500 µs, a lower bound; cyclictest's overflows (over 2 ms) are likewise counted as
 * 2 ms. Releases skipped because the receiver was still busy are not wake-up lateness and are only
 * listed.
 *
 * <p>The box is shared and its load changes from minute to minute, so the rows can be repeated in
 * interleaved rounds (notifier, notifier with spin, cyclictest, again...) to compare like with like.
 *
 * <p>Arguments: {@code [seconds per row, default 10] [spinNs for the spin row, default 50000]
 * [priority, default 81] [rounds, default 1]}.
 */
public final class NotifierLatencyHarness {

    private static final long PERIOD_NS = TimeUnit.MILLISECONDS.toNanos(1);
    private static final long WARMUP_S = 3;
    private static final Profile RECEIVER = Profile.of("loop");

    private NotifierLatencyHarness() {
    }

    public static void main(String[] args) throws Exception {
        long seconds = args.length > 0 ? Long.parseLong(args[0]) : 10;
        long spinNs = args.length > 1 ? Long.parseLong(args[1]) : 50_000;
        int priority = args.length > 2 ? Integer.parseInt(args[2]) : NotifierConfig.DEFAULT_PRIORITY;
        int rounds = args.length > 3 ? Integer.parseInt(args[3]) : 1;
        System.out.printf(Locale.ROOT, "Notifier lateness at %d Hz, %d s per row, SCHED_FIFO/%d, %d cores, java %s%n",
                TimeUnit.SECONDS.toNanos(1) / PERIOD_NS, seconds, priority,
                Runtime.getRuntime().availableProcessors(), Runtime.version());
        System.out.printf(Locale.ROOT, "%-22s %7s %8s %8s %8s %9s %9s%n", "row", "n", "skipped", "p50 us", "p99 us",
                "p99.9 us", "max us");

        for (int round = 1; round <= rounds; round++) {
            System.out.printf(Locale.ROOT, "round %d of %d, load average %s%n", round, rounds, loadAverage());
            measureNotifier("notifier", 0, priority, seconds);
            measureNotifier("notifier spin " + spinNs / 1000 + "us", spinNs, priority, seconds);
            measureCyclictest(priority, seconds);
        }
    }

    private static String loadAverage() {
        try {
            return java.nio.file.Files.readString(java.nio.file.Path.of("/proc/loadavg")).trim();
        } catch (IOException e) {
            return "unknown";
        }
    }

    private static void measureNotifier(String row, long spinNs, int priority, long seconds) {
        var config = NotifierConfig.defaults().withThreadPolicy(ThreadPolicy.fifo(priority)).withSpinNs(spinNs);
        try (var node = EtherwareNode.builder().nodeId("harness").scheduler(RealtimeScheduler::withDefaults).build()) {
            Notifier notifier = Notifier.install(node, config);
            node.add(RECEIVER, () -> (Component) (message, context) -> { });
            node.start();
            System.out.println("  " + notifier.threadGrant().map(grant -> grant.toLine()).orElse("no grant"));

            notifier.subscribe(Subscription.periodic("warmup", RECEIVER, Criticality.HIGH, PERIOD_NS));
            sleepSeconds(WARMUP_S);
            notifier.unsubscribe("warmup");

            notifier.subscribe(Subscription.periodic("measured", RECEIVER, Criticality.HIGH, PERIOD_NS));
            sleepSeconds(seconds);
            SubscriptionStats stats = notifier.unsubscribe("measured").orElseThrow();
            // Percentiles over every release, not only those sent: a release skipped for lateness
            // counts as maxLatenessNs, a lower bound of how late the thread really was.
            Histogram allReleasesNs = stats.latenessNs().copy();
            if (stats.skippedLate() > 0) {
                allReleasesNs.recordValueWithCount(stats.subscription().maxLatenessNs(), stats.skippedLate());
            }
            print(row, allReleasesNs, stats.skippedReleases());
            System.out.printf(Locale.ROOT, "  skipped: %d late (>= %d us), %d receiver busy, %d undeliverable%n",
                    stats.skippedLate(), stats.subscription().maxLatenessNs() / 1000, stats.skippedBusy(),
                    stats.skippedUndeliverable());
        }
    }

    private static void measureCyclictest(int priority, long seconds) throws IOException, InterruptedException {
        long loops = seconds * TimeUnit.SECONDS.toNanos(1) / PERIOD_NS;
        List<String> command = List.of("cyclictest", "-m", "-q", "-p", Integer.toString(priority), "-i",
                Long.toString(PERIOD_NS / 1000), "-l", Long.toString(loops), "-h", "2000");
        Process process;
        try {
            process = new ProcessBuilder(command).redirectErrorStream(true).start();
        } catch (IOException e) {
            System.out.println("cyclictest not installed (apt-get install rt-tests): " + e.getMessage());
            return;
        }
        // cyclictest -h prints one "<µs> <count>" line per bucket, then "# Max Latencies: ..." etc.
        var latencyNs = new Histogram(TimeUnit.SECONDS.toNanos(10), 3);
        long overflows = 0;
        var other = new ArrayList<String>();
        try (var reader = new BufferedReader(new InputStreamReader(process.getInputStream(), StandardCharsets.UTF_8))) {
            for (String line = reader.readLine(); line != null; line = reader.readLine()) {
                String[] fields = line.trim().split("\\s+");
                if (fields.length == 2 && fields[0].matches("\\d+") && fields[1].matches("\\d+")) {
                    long count = Long.parseLong(fields[1]);
                    if (count > 0) {
                        latencyNs.recordValueWithCount(Long.parseLong(fields[0]) * 1000, count);
                    }
                } else if (line.startsWith("# Histogram Overflows:")) {
                    overflows = Long.parseLong(line.substring(line.indexOf(':') + 1).trim());
                    if (overflows > 0) {
                        latencyNs.recordValueWithCount(TimeUnit.MILLISECONDS.toNanos(2), overflows);
                    }
                } else if (line.startsWith("# Max Latencies:")) {
                    other.add(line);
                } else if (!line.startsWith("#")) {
                    other.add(line);
                }
            }
        }
        int exit = process.waitFor();
        print("cyclictest", latencyNs, overflows);
        System.out.println("  " + String.join(" ", command) + " (exit " + exit + ", 1 us buckets; 'skipped' = overflows"
                + " >= 2 ms) " + String.join("; ", other));
    }

    private static void print(String row, Histogram latencyNs, long skipped) {
        System.out.printf(Locale.ROOT, "%-22s %7d %8d %8.1f %8.1f %9.1f %9.1f%n", row, latencyNs.getTotalCount(),
                skipped, latencyNs.getValueAtPercentile(50) / 1000.0, latencyNs.getValueAtPercentile(99) / 1000.0,
                latencyNs.getValueAtPercentile(99.9) / 1000.0, latencyNs.getMaxValue() / 1000.0);
    }

    private static void sleepSeconds(long seconds) {
        try {
            Thread.sleep(TimeUnit.SECONDS.toMillis(seconds));
        } catch (InterruptedException e) {
            Thread.currentThread().interrupt();
        }
    }
}
