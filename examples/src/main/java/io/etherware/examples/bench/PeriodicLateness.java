package io.etherware.examples.bench;

import io.etherware.core.component.Component;
import io.etherware.core.kernel.EtherwareNode;
import io.etherware.core.message.Criticality;
import io.etherware.core.message.Profile;
import io.etherware.rt.platform.AbsoluteSleeper;
import io.etherware.rt.platform.CpuSet;
import io.etherware.rt.platform.Platform;
import io.etherware.rt.platform.ThreadPolicy;
import io.etherware.rt.stats.LatencySnapshot;
import io.etherware.services.notifier.Notifier;
import io.etherware.services.notifier.NotifierConfig;
import io.etherware.services.notifier.Subscription;
import io.etherware.services.notifier.SubscriptionStats;
import java.io.BufferedReader;
import java.io.IOException;
import java.io.InputStreamReader;
import java.nio.charset.StandardCharsets;
import java.util.ArrayList;
import java.util.List;
import java.util.Locale;
import java.util.concurrent.CountDownLatch;
import java.util.concurrent.ScheduledFuture;
import java.util.concurrent.ScheduledThreadPoolExecutor;
import java.util.concurrent.TimeUnit;
import java.util.concurrent.atomic.AtomicLong;
import java.util.concurrent.atomic.AtomicReference;
import org.HdrHistogram.Histogram;
import org.HdrHistogram.Recorder;

/**
 * Section 1: lateness of a 1 kHz periodic release (when it ran minus when it was due), idle and
 * with every core loaded, for the Notifier (sleeping in the kernel to each release, its default, and
 * parking only), a {@link ScheduledThreadPoolExecutor#scheduleAtFixedRate}
 * on a thread at the same SCHED_FIFO priority, and {@code cyclictest} (rt-tests) at the same period
 * and priority when it is installed.
 *
 * <p>Every release is counted, so there is no coordinated omission: the Notifier skips a release
 * it reaches half a period late and counts it, and such releases enter the percentiles at that
 * bound (a lower bound of how late the thread was); the executor bursts to catch up, so each of
 * its runs is measured against its own due time; cyclictest's overflows (over 2 ms) count as 2 ms.
 *
 * <p>Runs on the caller's thread, which must be an ordinary (non-real-time) thread.
 */
final class PeriodicLateness {

    static final String SECTION = "1. periodic lateness 1 kHz";
    private static final Profile RECEIVER = Profile.of("bench-loop");
    private static final int CYCLICTEST_BUCKETS_US = 2000;
    /** The aim: the Notifier's p99 lateness within this factor of cyclictest's, same run, same state. */
    private static final double AIM_RATIO = 1.2;
    /** The executor's first release: long enough for {@code firstDueNs} to be set before it. */
    private static final long FIRST_DELAY_NS = TimeUnit.MILLISECONDS.toNanos(20);

    private final BenchConfig config;

    PeriodicLateness(BenchConfig config) {
        this.config = config;
    }

    /** Every row: the four variants idle, then the four loaded. */
    List<BenchRow> measure() throws InterruptedException, IOException {
        var rows = new ArrayList<BenchRow>();
        for (Condition condition : List.of(Condition.IDLE, Condition.LOADED)) {
            BenchRow notifier;
            BenchRow parking;
            BenchRow executor;
            BenchRow cyclictest;
            try (SpinLoad load = condition == Condition.LOADED ? SpinLoad.everyCore(allRowsNs()) : SpinLoad.none()) {
                notifier = notifier(condition, true);
                parking = notifier(condition, false);
                executor = executor(condition);
                cyclictest = cyclictest(condition);
            }
            if (cyclictest.measured() && cyclictest.percentiles().count() > 0) {
                double limit = AIM_RATIO * cyclictest.p99();
                notifier = notifier.judged(String.format(Locale.ROOT, "p99 <= %.1f x cyclictest p99 = %.1f us",
                        AIM_RATIO, limit), notifier.p99() <= limit);
            } else {
                notifier = notifier.withAim("p99 <= " + AIM_RATIO + " x cyclictest p99 (cyclictest not measured)");
            }
            rows.add(notifier);
            rows.add(parking);
            rows.add(executor);
            rows.add(cyclictest);
        }
        return rows;
    }

    private long allRowsNs() {
        return 4 * (config.periodicNs() + config.warmupNs()) + TimeUnit.SECONDS.toNanos(10);
    }

    /**
     * The Notifier at the bench's priority: with its default sleep ({@code kernelSleep}: parks, then
     * {@code clock_nanosleep} to the release) or parking only.
     */
    private BenchRow notifier(Condition condition, boolean kernelSleep) throws InterruptedException {
        var notifierConfig = NotifierConfig.defaults().withThreadPolicy(ThreadPolicy.fifo(config.priority()))
                .withKernelSleep(kernelSleep);
        try (var node = EtherwareNode.builder().nodeId("bench-notifier").scheduler(config::realtimeScheduler)
                .build()) {
            Notifier notifier = Notifier.install(node, notifierConfig);
            node.add(RECEIVER, () -> (Component) (message, context) -> { });
            node.start();
            notifier.subscribe(Subscription.periodic("warmup", RECEIVER, Criticality.HIGH, BenchConfig.PERIOD_NS));
            TimeUnit.NANOSECONDS.sleep(config.warmupNs());
            notifier.unsubscribe("warmup");
            notifier.subscribe(Subscription.periodic("measured", RECEIVER, Criticality.HIGH, BenchConfig.PERIOD_NS));
            TimeUnit.NANOSECONDS.sleep(config.periodicNs());
            SubscriptionStats stats = notifier.unsubscribe("measured").orElseThrow();
            LatencySnapshot allReleasesNs = stats.latenessNs().withSamples(stats.subscription().maxLatenessNs(),
                    stats.skippedLate());
            String grant = notifier.threadGrant().map(g -> g.granted().toString()).orElse("no thread");
            String sleep = kernelSleep && AbsoluteSleeper.isAvailable() ? "clock_nanosleep" : "parkNanos";
            return BenchRow.latency("periodic.notifier" + (kernelSleep ? "" : "-park") + "." + condition.id(), SECTION,
                    "Notifier (" + grant + ", " + sleep + ")",
                    condition.label(), "us", Percentiles.of(allReleasesNs), String.format(Locale.ROOT,
                            "%d skipped late (counted at %d us), %d skipped busy", stats.skippedLate(),
                            stats.subscription().maxLatenessNs() / 1000, stats.skippedBusy()));
        }
    }

    private BenchRow executor(Condition condition) throws InterruptedException {
        var policy = new AtomicReference<String>("not started");
        var executor = new ScheduledThreadPoolExecutor(1, task -> Thread.ofPlatform().name("bench-stpe").daemon(true)
                .unstarted(() -> {
                    // The same priority as the Notifier's thread, asked for by the thread itself.
                    var grant = Platform.current().configureCurrentThread(ThreadPolicy.fifo(config.priority()),
                            CpuSet.inherit());
                    policy.set(grant.granted().toString());
                    task.run();
                }));
        try {
            Recorder latenessNs = Histograms.recorderNs();
            long releases = (config.warmupNs() + config.periodicNs()) / BenchConfig.PERIOD_NS;
            long warmupReleases = config.warmupNs() / BenchConfig.PERIOD_NS;
            var done = new CountDownLatch(1);
            // The due times are the executor's own: the first read back from the future right after
            // scheduling (not a clock read before the call, which would count the lambda's linkage).
            var firstDueNs = new AtomicLong();
            var release = new long[1];
            Runnable task = () -> {
                long k = release[0]++;
                if (k >= warmupReleases && k < releases) {
                    latenessNs.recordValue(Histograms.clampNs(System.nanoTime() - (firstDueNs.get() + k * BenchConfig.PERIOD_NS)));
                } else if (k >= releases) {
                    done.countDown();
                }
            };
            ScheduledFuture<?> future = executor.scheduleAtFixedRate(task, FIRST_DELAY_NS, BenchConfig.PERIOD_NS,
                    TimeUnit.NANOSECONDS);
            firstDueNs.set(System.nanoTime() + future.getDelay(TimeUnit.NANOSECONDS));
            if (!done.await(config.warmupNs() + config.periodicNs() + TimeUnit.SECONDS.toNanos(30), TimeUnit.NANOSECONDS)) {
                throw new IllegalStateException("the executor's releases did not finish");
            }
            future.cancel(false);
            return BenchRow.latency("periodic.executor." + condition.id(), SECTION,
                    "ScheduledThreadPoolExecutor.scheduleAtFixedRate (" + policy.get() + ")", condition.label(), "us",
                    Percentiles.of(latenessNs.getIntervalHistogram()), "due times from the executor (first read back from its future)");
        } finally {
            executor.shutdownNow();
        }
    }

    private BenchRow cyclictest(Condition condition) throws IOException, InterruptedException {
        String id = "periodic.cyclictest." + condition.id();
        long loops = config.periodicNs() / BenchConfig.PERIOD_NS;
        List<String> command = List.of("cyclictest", "-m", "-q", "-p", Integer.toString(config.priority()), "-i",
                Long.toString(BenchConfig.PERIOD_NS / 1000), "-l", Long.toString(loops), "-h",
                Integer.toString(CYCLICTEST_BUCKETS_US));
        Process process;
        try {
            process = new ProcessBuilder(command).redirectErrorStream(true).start();
        } catch (IOException e) {
            return BenchRow.notMeasured(id, SECTION, "cyclictest", condition.label(),
                    "not installed (apt-get install rt-tests)");
        }
        // cyclictest -h prints one "<us> <count>" line per bucket, then "# Histogram Overflows: n".
        Histogram latencyNs = Histograms.latencyNs();
        var otherLines = new ArrayList<String>();
        try (var reader = new BufferedReader(new InputStreamReader(process.getInputStream(), StandardCharsets.UTF_8))) {
            for (String line = reader.readLine(); line != null; line = reader.readLine()) {
                String[] fields = line.trim().split("\\s+");
                if (fields.length == 2 && fields[0].matches("\\d+") && fields[1].matches("\\d+")) {
                    long count = Long.parseLong(fields[1]);
                    if (count > 0) {
                        latencyNs.recordValueWithCount(TimeUnit.MICROSECONDS.toNanos(Long.parseLong(fields[0])), count);
                    }
                } else if (line.startsWith("# Histogram Overflows:")) {
                    long overflows = Long.parseLong(line.substring(line.indexOf(':') + 1).trim().split("\\s+")[0]);
                    if (overflows > 0) {
                        latencyNs.recordValueWithCount(TimeUnit.MICROSECONDS.toNanos(CYCLICTEST_BUCKETS_US), overflows);
                    }
                } else if (!line.startsWith("#") && !line.isBlank()) {
                    otherLines.add(line.trim());
                }
            }
        }
        int exit = process.waitFor();
        if (exit != 0 || latencyNs.getTotalCount() == 0) {
            return BenchRow.notMeasured(id, SECTION, "cyclictest", condition.label(),
                    "cyclictest failed (exit " + exit + "): " + String.join(" ", otherLines));
        }
        return BenchRow.latency(id, SECTION, "cyclictest -p " + config.priority(), condition.label(), "us",
                Percentiles.of(latencyNs), "1 us buckets, overflows counted at 2 ms");
    }
}
