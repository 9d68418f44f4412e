package io.etherware.rt.scheduling;

import io.etherware.core.message.Criticality;
import io.etherware.core.message.QoS;
import io.etherware.core.scheduler.Scheduler;
import io.etherware.core.time.NodeClock;
import io.etherware.rt.platform.CpuSet;
import io.etherware.rt.platform.Platform;
import io.etherware.rt.platform.ThreadPolicy;
import java.util.List;
import java.util.Locale;
import java.util.concurrent.Semaphore;
import java.util.concurrent.TimeUnit;
import java.util.concurrent.atomic.AtomicBoolean;
import java.util.concurrent.locks.LockSupport;
import java.util.function.Supplier;
import org.HdrHistogram.Histogram;

/**
 * HIGH dispatch latency (submit → start of the component's handler) at 1 kHz, with and without a
 * LOW flood saturating the CPUs, for the real-time scheduler (Table II, Algorithm 1) and the FIFO
 * baseline, in the same run. Not part of the test suite; run with {@code java -cp} (see the
 * module's report for the exact command).
 *
 * <p>The flood: LOW messages to one component, each burning {@value #LOW_JOB_US} µs of CPU, kept
 * {@value #LOW_BACKLOG} deep in the queue (so the LOW dispatcher is never idle), plus one ordinary
 * SCHED_OTHER burner thread per core. The HIGH sender stands for the Notifier: a thread at
 * SCHED_FIFO {@value #SENDER_PRIORITY} when granted, sleeping to absolute 1 ms release times.
 *
 * <p>Arguments: {@code [seconds per measurement, default 5]}.
 */
public final class DispatchLatencyHarness {

    private static final long PERIOD_NS = TimeUnit.MILLISECONDS.toNanos(1);
    private static final long LOW_JOB_US = 100;
    private static final int LOW_BACKLOG = 32;
    private static final int SENDER_PRIORITY = 85;
    private static final long WARMUP_S = 2;

    private DispatchLatencyHarness() {
    }

    public static void main(String[] args) throws Exception {
        long seconds = args.length > 0 ? Long.parseLong(args[0]) : 5;
        System.out.printf(Locale.ROOT, "HIGH dispatch latency, submit -> handler start, 1 kHz, %d s per row, %d cores,"
                + " java %s%n", seconds, Runtime.getRuntime().availableProcessors(), Runtime.version());
        System.out.printf(Locale.ROOT, "%-14s %-6s %7s %9s %9s %9s %9s%n", "scheduler", "load", "n", "p50 us", "p99 us",
                "p99.9 us", "max us");
        int lastCpu = Runtime.getRuntime().availableProcessors() - 1;
        // Same-CPU variant: the HIGH dispatcher and the sender share one CPU, so the hand-off is a
        // local wake-up instead of an inter-processor interrupt to another (possibly idle) vCPU.
        ThreadSchedulingRule pinned = new ThreadSchedulingRule(List.of(DispatcherSpec.nonRealtime(),
                DispatcherSpec.fifo(ThreadSchedulingRule.HIGH_PRIORITY).on(CpuSet.of(lastCpu)),
                DispatcherSpec.fifo(ThreadSchedulingRule.MIDDLE_PRIORITY),
                DispatcherSpec.fifo(ThreadSchedulingRule.LOW_PRIORITY)));
        List<Variant> variants = List.of(
                new Variant("rt", RealtimeScheduler::withDefaults, CpuSet.inherit()),
                new Variant("rt-pinned", () -> new RealtimeScheduler(RealtimeSchedulerConfig.builder().name("pinned")
                        .threadSchedulingRule(pinned).build()), CpuSet.of(lastCpu)),
                new Variant("fifo-baseline", SingleThreadFifoScheduler::new, CpuSet.inherit()));
        for (Variant variant : variants) {
            Scheduler scheduler = variant.scheduler().get();
            var run = new HarnessRun(scheduler, variant.senderCpus());
            print(variant.name(), "warmup", run.measure(WARMUP_S, false));
            print(variant.name(), "idle", run.measure(seconds, false));
            print(variant.name(), "flood", run.measure(seconds, true));
            if (scheduler instanceof RealtimeScheduler realtime) {
                realtime.platformReport().lines().forEach(line -> System.out.println("  " + line));
                DispatcherStats high = realtime.stats().dispatcher(CriticalityDeadlinePlacement.HIGH_DISPATCHER);
                System.out.printf(Locale.ROOT, "  dispatcher 1 stats: %d run, start latency p99 %.1f us (incl. warm-up),"
                        + " %d deadline misses overall%n", high.jobsRun(),
                        high.startLatencyNs().getValueAtPercentile(99) / 1000.0, realtime.stats().deadlineMisses());
            }
            run.close();
        }
    }

    private record Variant(String name, Supplier<Scheduler> scheduler, CpuSet senderCpus) {
    }

    private static void print(String scheduler, String load, Histogram latencyNs) {
        System.out.printf(Locale.ROOT, "%-14s %-6s %7d %9.1f %9.1f %9.1f %9.1f%n", scheduler, load,
                latencyNs.getTotalCount(), latencyNs.getValueAtPercentile(50) / 1000.0,
                latencyNs.getValueAtPercentile(99) / 1000.0, latencyNs.getValueAtPercentile(99.9) / 1000.0,
                latencyNs.getMaxValue() / 1000.0);
    }

    /** One scheduler with its fake kernel, measured several times. */
    private static final class HarnessRun {
        private final Scheduler scheduler;
        private final CpuSet senderCpus;
        private final NodeClock clock = NodeClock.system();
        private final Semaphore lowBacklog = new Semaphore(LOW_BACKLOG);
        private volatile Histogram highLatencyNs;

        HarnessRun(Scheduler scheduler, CpuSet senderCpus) {
            this.scheduler = scheduler;
            this.senderCpus = senderCpus;
            var kernel = new FakeKernel(false)
                    .on("A", (job, startNs) -> highLatencyNs.recordValue(Math.max(0, startNs - job.releaseNs())))
                    .on("B", (job, startNs) -> {
                        long endNs = System.nanoTime() + TimeUnit.MICROSECONDS.toNanos(LOW_JOB_US);
                        while (System.nanoTime() < endNs) {
                            Thread.onSpinWait();
                        }
                        lowBacklog.release();
                    });
            kernel.bind(scheduler);
            scheduler.start(kernel, clock);
        }

        Histogram measure(long seconds, boolean flood) throws InterruptedException {
            var latencyNs = new Histogram(TimeUnit.SECONDS.toNanos(10), 3);
            highLatencyNs = latencyNs;
            var stop = new AtomicBoolean();
            Thread producer = null;
            Burners burners = Burners.none();
            if (flood) {
                burners = Burners.start(Runtime.getRuntime().availableProcessors(), (seconds + 2) * 1000);
                producer = Thread.ofPlatform().name("low-flood").start(() -> {
                    while (!stop.get()) {
                        try {
                            if (lowBacklog.tryAcquire(10, TimeUnit.MILLISECONDS)) {
                                scheduler.submit(TestJobs.job("B", QoS.periodic(Criticality.LOW, PERIOD_NS * 100),
                                        clock.nanoTime()));
                            }
                        } catch (InterruptedException e) {
                            return;
                        }
                    }
                });
                Thread.sleep(200);
            }
            Thread sender = Thread.ofPlatform().name("high-sender").start(() -> send(seconds));
            sender.join();
            stop.set(true);
            if (producer != null) {
                producer.join();
            }
            burners.stop();
            Thread.sleep(100);
            return latencyNs.copy();
        }

        private void send(long seconds) {
            Platform.current().configureCurrentThread(ThreadPolicy.fifo(SENDER_PRIORITY), senderCpus);
            long count = seconds * TimeUnit.SECONDS.toNanos(1) / PERIOD_NS;
            long nextNs = clock.nanoTime() + PERIOD_NS;
            for (long i = 0; i < count; i++) {
                LockSupport.parkNanos(nextNs - clock.nanoTime());
                scheduler.submit(TestJobs.job("A", QoS.periodic(Criticality.HIGH, PERIOD_NS), clock.nanoTime()));
                nextNs += PERIOD_NS;
            }
        }

        void close() {
            scheduler.shutdown(TimeUnit.SECONDS.toNanos(2));
        }
    }
}
