package io.etherware.examples.bench;

import io.etherware.core.kernel.EtherwareNode;
import io.etherware.core.message.Contents;
import io.etherware.core.message.Criticality;
import io.etherware.core.message.Profile;
import io.etherware.core.message.QoS;
import io.etherware.core.scheduler.FifoScheduler;
import io.etherware.core.scheduler.Scheduler;
import io.etherware.rt.platform.CpuSet;
import io.etherware.rt.platform.Platform;
import io.etherware.rt.platform.ThreadPolicy;
import io.etherware.rt.scheduling.DispatcherSpec;
import io.etherware.rt.scheduling.RealtimeScheduler;
import io.etherware.rt.scheduling.RealtimeSchedulerConfig;
import io.etherware.rt.scheduling.ThreadSchedulingRule;
import java.time.Duration;
import java.util.ArrayList;
import java.util.List;
import java.util.concurrent.ArrayBlockingQueue;
import java.util.concurrent.Semaphore;
import java.util.concurrent.TimeUnit;
import java.util.concurrent.atomic.AtomicBoolean;
import java.util.concurrent.locks.LockSupport;
import java.util.function.Supplier;
import org.HdrHistogram.Histogram;
import org.HdrHistogram.Recorder;

/**
 * Section 2: HIGH dispatch latency at 1 kHz, {@code EtherwareNode.send} to the first line of the
 * component's {@code onMessage}, idle and under a LOW flood, for the original {@link FifoScheduler},
 * the {@link RealtimeScheduler} (Table II, Algorithm 1), the same with its HIGH dispatcher and the
 * sender pinned to one CPU, and a bare {@link ArrayBlockingQueue} hand-off between two threads at
 * the HIGH dispatcher's priority (the floor Java offers).
 *
 * <p>The HIGH sender stands for the Notifier: a thread at SCHED_FIFO {@value #SENDER_PRIORITY}
 * (when granted) sleeping to absolute 1 ms release times. The load is open-loop: the sender never
 * waits for a receiver, and every message is timed from its own send, so a stalled receiver shows
 * in every message queued behind it and there is no coordinated omission to correct (HdrHistogram's
 * {@code recordValueWithExpectedInterval} would count each such message twice). The sender's own
 * lateness is what section 1 measures.
 *
 * <p>The flood: LOW messages, each burning {@value #LOW_JOB_US} µs of CPU, released one every
 * {@value #LOW_RELEASE_US} µs (at most {@value #LOW_BACKLOG} waiting), so the LOW dispatcher
 * (SCHED_FIFO 60) is busy half of the time and never keeps a CPU for long; one ordinary spinning
 * thread per core loads the rest. Runs on the caller's (ordinary) thread.
 */
final class DispatchLatency {

    static final String SECTION = "2. HIGH dispatch latency 1 kHz";
    private static final long LOW_JOB_US = 100;
    private static final long LOW_RELEASE_US = 200;
    private static final int LOW_BACKLOG = 32;
    private static final int SENDER_PRIORITY = 85;
    private static final Profile HIGH_TARGET = Profile.of("bench-high");
    private static final Profile LOW_TARGET = Profile.of("bench-low");
    private static final QoS HIGH = QoS.periodic(Criticality.HIGH, BenchConfig.PERIOD_NS);
    private static final QoS LOW = QoS.periodic(Criticality.LOW, BenchConfig.PERIOD_NS * 100);

    /** The HIGH message: when it was sent, on the node's clock. */
    record Ping(long sentNs) implements Contents {
    }

    /** A LOW message of the flood. */
    record Burn() implements Contents {
    }

    private final BenchConfig config;

    DispatchLatency(BenchConfig config) {
        this.config = config;
    }

    List<BenchRow> measure() throws InterruptedException {
        var rows = new ArrayList<BenchRow>();
        // Pinned: the HIGH dispatcher and the sender share the last CPU, so the hand-off is a local
        // wake-up instead of an inter-processor interrupt to another (possibly idle) vCPU.
        CpuSet lastCpu = CpuSet.of(Runtime.getRuntime().availableProcessors() - 1);
        Supplier<Scheduler> pinned = () -> config.realtimeScheduler(RealtimeSchedulerConfig.builder().name("pinned")
                .threadSchedulingRule(new ThreadSchedulingRule(List.of(DispatcherSpec.nonRealtime(),
                        DispatcherSpec.fifo(ThreadSchedulingRule.HIGH_PRIORITY).on(lastCpu),
                        DispatcherSpec.fifo(ThreadSchedulingRule.MIDDLE_PRIORITY),
                        DispatcherSpec.fifo(ThreadSchedulingRule.LOW_PRIORITY)))));
        List<Target> targets = List.of(
                new Target("fifo", "FifoScheduler (original Etherware)",
                        () -> new NodeTarget(FifoScheduler::new, CpuSet.inherit())),
                new Target("rt", "RealtimeScheduler (Table II)",
                        () -> new NodeTarget(config::realtimeScheduler, CpuSet.inherit())),
                new Target("rt-pinned", "RealtimeScheduler (Table II), HIGH dispatcher and sender on CPU "
                        + (Runtime.getRuntime().availableProcessors() - 1), () -> new NodeTarget(pinned, lastCpu)),
                new Target("queue", "ArrayBlockingQueue hand-off (floor)", QueueTarget::new));
        for (Target target : targets) {
            try (Bench bench = target.factory().get()) {
                bench.measure(config.warmupNs(), false);
                for (Condition condition : List.of(Condition.IDLE, Condition.FLOOD)) {
                    Histogram latencyNs = bench.measure(config.dispatchNs(), condition == Condition.FLOOD);
                    BenchRow row = BenchRow.latency("dispatch." + target.id() + "." + condition.id(), SECTION,
                            target.name() + bench.grants(), condition.label(), "us", Percentiles.of(latencyNs),
                            "open loop: every message timed, none omitted");
                    if (target.id().equals("rt") && condition == Condition.FLOOD) {
                        row = row.judged("p99 <= 30 us under the flood", row.p99() <= 30);
                    }
                    rows.add(row);
                }
            }
        }
        return rows;
    }

    private record Target(String id, String name, Supplier<Bench> factory) {
    }

    /** HIGH messages to one receiver and a LOW flood to another, measured several times. */
    private abstract static class Bench implements AutoCloseable {
        private final Recorder highLatencyNs = Histograms.recorderNs();
        private final Semaphore lowBacklog = new Semaphore(LOW_BACKLOG);
        private final CpuSet senderCpus;
        volatile String senderPolicy = "";

        Bench(CpuSet senderCpus) {
            this.senderCpus = senderCpus;
        }

        abstract void sendHigh(long nowNs);

        abstract void sendLow();

        /** The OS policies the threads got, for the row's name. */
        String grants() {
            return senderPolicy.isEmpty() ? "" : "; sender " + senderPolicy;
        }

        /** The HIGH receiver: one sample, recorded wait-free. */
        final void onHigh(long latencyNs) {
            highLatencyNs.recordValue(Histograms.clampNs(latencyNs));
        }

        /** The LOW receiver: burns {@value #LOW_JOB_US} µs, then frees a backlog slot. */
        final void onLow() {
            SpinLoad.burn(TimeUnit.MICROSECONDS.toNanos(LOW_JOB_US));
            lowBacklog.release();
        }

        Histogram measure(long durationNs, boolean flood) throws InterruptedException {
            var stop = new AtomicBoolean();
            Thread producer = null;
            try (SpinLoad load = flood ? SpinLoad.everyCore(durationNs + TimeUnit.SECONDS.toNanos(5)) : SpinLoad.none()) {
                if (flood) {
                    producer = Thread.ofPlatform().name("bench-low-flood").start(() -> flood(stop));
                    Thread.sleep(100);
                }
                highLatencyNs.reset();
                Thread sender = Thread.ofPlatform().name("bench-high-sender").start(() -> sendPeriodically(durationNs));
                sender.join();
                Thread.sleep(50); // let the last HIGH message run
                Histogram latencyNs = highLatencyNs.getIntervalHistogram();
                stop.set(true);
                if (producer != null) {
                    producer.join();
                }
                return latencyNs;
            }
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

        private void sendPeriodically(long durationNs) {
            var grant = Platform.current().configureCurrentThread(ThreadPolicy.fifo(SENDER_PRIORITY), senderCpus);
            senderPolicy = grant.granted().toString();
            long count = durationNs / BenchConfig.PERIOD_NS;
            long nextNs = System.nanoTime() + BenchConfig.PERIOD_NS;
            for (long i = 0; i < count; i++) {
                LockSupport.parkNanos(nextNs - System.nanoTime());
                sendHigh(System.nanoTime());
                nextNs += BenchConfig.PERIOD_NS;
            }
        }

        @Override
        public abstract void close();
    }

    /** A real node: EtherwareNode.send to the start of the component's onMessage. */
    private static final class NodeTarget extends Bench {
        private final EtherwareNode node;

        NodeTarget(Supplier<Scheduler> scheduler, CpuSet senderCpus) {
            super(senderCpus);
            node = EtherwareNode.builder().nodeId("bench-dispatch").scheduler(scheduler)
                    .drainTimeout(Duration.ofSeconds(2)).build();
            node.add(HIGH_TARGET, () -> (message, context) ->
                    onHigh(System.nanoTime() - message.contentsAs(Ping.class).sentNs()));
            node.add(LOW_TARGET, () -> (message, context) -> onLow());
            node.start();
        }

        @Override
        void sendHigh(long nowNs) {
            node.send(HIGH_TARGET, new Ping(nowNs), HIGH);
        }

        @Override
        void sendLow() {
            node.send(LOW_TARGET, new Burn(), LOW);
        }

        @Override
        public void close() {
            node.close();
        }
    }

    /**
     * The floor: two consumer threads taking from {@link ArrayBlockingQueue}s, HIGH at the HIGH
     * dispatcher's priority and LOW at the LOW dispatcher's, with nothing between send and handler.
     */
    private static final class QueueTarget extends Bench {
        private static final long STOP = Long.MIN_VALUE;
        private final ArrayBlockingQueue<Long> high = new ArrayBlockingQueue<>(1024);
        private final ArrayBlockingQueue<Long> low = new ArrayBlockingQueue<>(LOW_BACKLOG + 1);
        private final Thread highThread;
        private final Thread lowThread;
        private volatile String highPolicy = "";

        QueueTarget() {
            super(CpuSet.inherit());
            highThread = Thread.ofPlatform().name("bench-queue-high").daemon(true).start(() -> {
                highPolicy = Platform.current().configureCurrentThread(
                        ThreadPolicy.fifo(ThreadSchedulingRule.HIGH_PRIORITY), CpuSet.inherit()).granted().toString();
                consume(high, sentNs -> onHigh(System.nanoTime() - sentNs));
            });
            lowThread = Thread.ofPlatform().name("bench-queue-low").daemon(true).start(() -> {
                Platform.current().configureCurrentThread(ThreadPolicy.fifo(ThreadSchedulingRule.LOW_PRIORITY),
                        CpuSet.inherit());
                consume(low, ignored -> onLow());
            });
        }

        private static void consume(ArrayBlockingQueue<Long> queue, java.util.function.LongConsumer handler) {
            try {
                for (long value = queue.take(); value != STOP; value = queue.take()) {
                    handler.accept(value);
                }
            } catch (InterruptedException e) {
                Thread.currentThread().interrupt();
            }
        }

        @Override
        String grants() {
            return " (" + highPolicy + ")" + super.grants();
        }

        @Override
        void sendHigh(long nowNs) {
            high.offer(nowNs);
        }

        @Override
        void sendLow() {
            low.offer(0L);
        }

        @Override
        public void close() {
            high.offer(STOP);
            low.offer(STOP);
            try {
                highThread.join(2_000);
                lowThread.join(2_000);
            } catch (InterruptedException e) {
                Thread.currentThread().interrupt();
            }
        }
    }
}
