package io.etherware.rt.scheduling;

import io.etherware.core.kernel.EtherwareNode;
import io.etherware.core.message.Contents;
import io.etherware.core.message.Criticality;
import io.etherware.core.message.Profile;
import io.etherware.core.message.QoS;
import io.etherware.core.scheduler.FifoScheduler;
import io.etherware.core.scheduler.Scheduler;
import io.etherware.core.time.NodeClock;
import io.etherware.rt.platform.CpuSet;
import io.etherware.rt.platform.Platform;
import io.etherware.rt.platform.ThreadPolicy;
import java.time.Duration;
import java.util.List;
import java.util.Locale;
import java.util.concurrent.Semaphore;
import java.util.concurrent.TimeUnit;
import java.util.concurrent.atomic.AtomicBoolean;
import java.util.concurrent.locks.LockSupport;
import java.util.function.Supplier;
import org.HdrHistogram.Histogram;
import org.HdrHistogram.Recorder;

/**
 * HIGH dispatch latency at 1 kHz, with and without a LOW flood saturating the CPUs, for the
 * real-time scheduler (Table II, Algorithm 1) and the kernel's {@link FifoScheduler} baseline, in
 * the same run, at two levels:
 * <ul>
 *   <li>{@code spi}: the scheduler alone behind a {@link FakeKernel}; latency is
 *       {@code Scheduler.submit} to the start of the job;</li>
 *   <li>{@code node}: a real {@link EtherwareNode}; latency is {@code EtherwareNode.send} to the
 *       first line of the component's {@code onMessage} (registry lookup, job, gate and shell
 *       included).</li>
 * </ul>
 * Not part of the test suite. Arguments: {@code [seconds per measurement, default 5]}. From the
 * repository root, as root for SCHED_FIFO (about a minute with 4 s rows):
 * <pre>{@code
 * ./mvnw -q -pl etherware-rt -am test-compile
 * CP=etherware-rt/target/test-classes:etherware-rt/target/classes:etherware-core/target/classes:$(find \
 *   ~/.m2/repository -name slf4j-api-2.0.20.jar -o -name slf4j-simple-2.0.20.jar -o -name HdrHistogram-2.2.2.jar \
 *   | paste -sd:)
 * $JAVA_HOME/bin/java --enable-native-access=ALL-UNNAMED -Xms256m -Xmx256m -XX:+AlwaysPreTouch \
 *   -Dorg.slf4j.simpleLogger.defaultLogLevel=warn -cp "$CP" io.etherware.rt.scheduling.DispatchLatencyHarness 4
 * }</pre>
 *
 * <p>The flood: LOW messages to component B, each burning {@value #LOW_JOB_US} µs of CPU, released
 * one every {@value #LOW_RELEASE_US} µs (at most {@value #LOW_BACKLOG} queued), so the LOW
 * dispatcher, SCHED_FIFO 60, is busy half of the time: a real-time thread is never left burning a
 * CPU for seconds. One ordinary SCHED_OTHER burner thread per core saturates the rest. The HIGH
 * sender stands for the Notifier: a thread at SCHED_FIFO {@value #SENDER_PRIORITY} when granted,
 * sleeping to absolute 1 ms release times.
 */
public final class DispatchLatencyHarness {

    private static final long PERIOD_NS = TimeUnit.MILLISECONDS.toNanos(1);
    private static final long LOW_JOB_US = 100;
    private static final long LOW_RELEASE_US = 200;
    private static final int LOW_BACKLOG = 32;
    private static final int SENDER_PRIORITY = 85;
    private static final long WARMUP_S = 2;
    private static final long MAX_LATENCY_NS = TimeUnit.SECONDS.toNanos(10);
    private static final Profile A = Profile.of("a");
    private static final Profile B = Profile.of("b");
    private static final QoS HIGH = QoS.periodic(Criticality.HIGH, PERIOD_NS);
    private static final QoS LOW = QoS.periodic(Criticality.LOW, PERIOD_NS * 100);

    private DispatchLatencyHarness() {
    }

    /** The HIGH message of the node level: when it was sent, on the node's clock. */
    record Ping(long sentNs) implements Contents {
    }

    /** A LOW message of the node level. */
    record Burn() implements Contents {
    }

    private record Variant(String level, String name, Supplier<Scheduler> scheduler, CpuSet senderCpus) {
    }

    public static void main(String[] args) throws Exception {
        long seconds = args.length > 0 ? Long.parseLong(args[0]) : 5;
        System.out.printf(Locale.ROOT, "HIGH dispatch latency at 1 kHz, %d s per row, %d cores, java %s%n", seconds,
                Runtime.getRuntime().availableProcessors(), Runtime.version());
        System.out.printf(Locale.ROOT, "%-5s %-10s %-6s %7s %9s %9s %9s %9s%n", "level", "scheduler", "load", "n",
                "p50 us", "p99 us", "p99.9 us", "max us");
        int lastCpu = Runtime.getRuntime().availableProcessors() - 1;
        // Same-CPU variant: the HIGH dispatcher and the sender share one CPU, so the hand-off is a
        // local wake-up instead of an inter-processor interrupt to another (possibly idle) vCPU.
        ThreadSchedulingRule pinned = new ThreadSchedulingRule(List.of(DispatcherSpec.nonRealtime(),
                DispatcherSpec.fifo(ThreadSchedulingRule.HIGH_PRIORITY).on(CpuSet.of(lastCpu)),
                DispatcherSpec.fifo(ThreadSchedulingRule.MIDDLE_PRIORITY),
                DispatcherSpec.fifo(ThreadSchedulingRule.LOW_PRIORITY)));
        Supplier<Scheduler> pinnedScheduler = () -> new RealtimeScheduler(RealtimeSchedulerConfig.builder()
                .name("pinned").threadSchedulingRule(pinned).build());
        List<Variant> variants = List.of(
                new Variant("spi", "rt", RealtimeScheduler::withDefaults, CpuSet.inherit()),
                new Variant("spi", "rt-pinned", pinnedScheduler, CpuSet.of(lastCpu)),
                new Variant("spi", "fifo", FifoScheduler::new, CpuSet.inherit()),
                new Variant("node", "rt", RealtimeScheduler::withDefaults, CpuSet.inherit()),
                new Variant("node", "rt-pinned", pinnedScheduler, CpuSet.of(lastCpu)),
                new Variant("node", "fifo", FifoScheduler::new, CpuSet.inherit()));
        for (Variant variant : variants) {
            Scheduler scheduler = variant.scheduler().get();
            try (Bench bench = variant.level().equals("node") ? new NodeBench(scheduler, variant.senderCpus())
                    : new SpiBench(scheduler, variant.senderCpus())) {
                print(variant, "warmup", bench.measure(WARMUP_S, false));
                print(variant, "idle", bench.measure(seconds, false));
                print(variant, "flood", bench.measure(seconds, true));
            }
            if (scheduler instanceof RealtimeScheduler realtime) {
                realtime.platformReport().lines().forEach(line -> System.out.println("    " + line));
                DispatcherStats high = realtime.stats().dispatcher(CriticalityDeadlinePlacement.HIGH_DISPATCHER);
                DispatcherStats low = realtime.stats().dispatcher(CriticalityDeadlinePlacement.LOW_DISPATCHER);
                System.out.printf(Locale.ROOT, "    dispatcher 1: %d run, release-to-start p99 %.1f us; dispatcher 3:"
                        + " %d run; %d deadline misses (all rows incl. warm-up)%n", high.jobsRun(),
                        high.startLatencyNs().getValueAtPercentile(99) / 1000.0, low.jobsRun(),
                        realtime.stats().deadlineMisses());
            }
        }
    }

    private static void print(Variant variant, String load, Histogram latencyNs) {
        System.out.printf(Locale.ROOT, "%-5s %-10s %-6s %7d %9.1f %9.1f %9.1f %9.1f%n", variant.level(),
                variant.name(), load, latencyNs.getTotalCount(), latencyNs.getValueAtPercentile(50) / 1000.0,
                latencyNs.getValueAtPercentile(99) / 1000.0, latencyNs.getValueAtPercentile(99.9) / 1000.0,
                latencyNs.getMaxValue() / 1000.0);
    }

    /** One scheduler, HIGH messages to component A and a LOW flood to B, measured several times. */
    private abstract static class Bench implements AutoCloseable {
        final NodeClock clock = NodeClock.system();
        private final Recorder highLatencyNs = new Recorder(MAX_LATENCY_NS, 3);
        private final Semaphore lowBacklog = new Semaphore(LOW_BACKLOG);
        private final CpuSet senderCpus;

        Bench(CpuSet senderCpus) {
            this.senderCpus = senderCpus;
        }

        abstract void sendHigh();

        abstract void sendLow();

        /** A's handler: one HIGH latency sample (recorded wait-free, read by the main thread). */
        final void onHigh(long latencyNs) {
            highLatencyNs.recordValue(Math.clamp(latencyNs, 0, MAX_LATENCY_NS));
        }

        /** B's handler: burns {@value #LOW_JOB_US} µs (bounded), then frees a backlog slot. */
        final void onLow() {
            long endNs = System.nanoTime() + TimeUnit.MICROSECONDS.toNanos(LOW_JOB_US);
            while (System.nanoTime() < endNs) {
                Thread.onSpinWait();
            }
            lowBacklog.release();
        }

        Histogram measure(long seconds, boolean flood) throws InterruptedException {
            var stop = new AtomicBoolean();
            Thread producer = null;
            Burners burners = Burners.none();
            if (flood) {
                burners = Burners.start(Runtime.getRuntime().availableProcessors(), (seconds + 2) * 1000);
                producer = Thread.ofPlatform().name("low-flood").start(() -> flood(stop));
                Thread.sleep(200);
            }
            highLatencyNs.reset();
            Thread sender = Thread.ofPlatform().name("high-sender").start(() -> sendPeriodically(seconds));
            sender.join();
            Thread.sleep(100); // let the last HIGH message run
            Histogram latencyNs = highLatencyNs.getIntervalHistogram();
            stop.set(true);
            if (producer != null) {
                producer.join();
            }
            burners.stop();
            Thread.sleep(100);
            return latencyNs;
        }

        /** LOW releases at a fixed rate; a release finding the backlog full is skipped, not queued. */
        private void flood(AtomicBoolean stop) {
            long startNs = System.nanoTime();
            long released = 0;
            while (!stop.get()) {
                LockSupport.parkNanos(TimeUnit.MILLISECONDS.toNanos(1));
                long due = (System.nanoTime() - startNs) / TimeUnit.MICROSECONDS.toNanos(LOW_RELEASE_US);
                for (; released < due; released++) {
                    if (lowBacklog.tryAcquire()) {
                        sendLow();
                    }
                }
            }
        }

        private void sendPeriodically(long seconds) {
            Platform.current().configureCurrentThread(ThreadPolicy.fifo(SENDER_PRIORITY), senderCpus);
            long count = TimeUnit.SECONDS.toNanos(seconds) / PERIOD_NS;
            long nextNs = clock.nanoTime() + PERIOD_NS;
            for (long i = 0; i < count; i++) {
                LockSupport.parkNanos(nextNs - clock.nanoTime());
                sendHigh();
                nextNs += PERIOD_NS;
            }
        }
    }

    /** The scheduler alone: submit to job start, through the test kernel. */
    private static final class SpiBench extends Bench {
        private final Scheduler scheduler;

        SpiBench(Scheduler scheduler, CpuSet senderCpus) {
            super(senderCpus);
            this.scheduler = scheduler;
            var kernel = new FakeKernel(false)
                    .on("a", (job, startNs) -> onHigh(startNs - job.releaseNs()))
                    .on("b", (job, startNs) -> onLow());
            kernel.bind(scheduler);
            scheduler.start(kernel, clock);
        }

        @Override
        void sendHigh() {
            scheduler.submit(TestJobs.job("a", HIGH, clock.nanoTime()));
        }

        @Override
        void sendLow() {
            scheduler.submit(TestJobs.job("b", LOW, clock.nanoTime()));
        }

        @Override
        public void close() {
            scheduler.shutdown(TimeUnit.SECONDS.toNanos(2));
        }
    }

    /** A real node: EtherwareNode.send to the start of the component's onMessage. */
    private static final class NodeBench extends Bench {
        private final EtherwareNode node;

        NodeBench(Scheduler scheduler, CpuSet senderCpus) {
            super(senderCpus);
            node = EtherwareNode.builder().nodeId("harness").scheduler(() -> scheduler).clock(clock)
                    .drainTimeout(Duration.ofSeconds(2)).build();
            node.add(A, () -> (message, context) -> onHigh(clock.nanoTime() - message.contentsAs(Ping.class).sentNs()));
            node.add(B, () -> (message, context) -> onLow());
            node.start();
        }

        @Override
        void sendHigh() {
            node.send(A, new Ping(clock.nanoTime()), HIGH);
        }

        @Override
        void sendLow() {
            node.send(B, new Burn(), LOW);
        }

        @Override
        public void close() {
            node.close();
        }
    }
}
