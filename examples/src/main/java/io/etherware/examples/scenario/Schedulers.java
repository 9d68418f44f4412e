package io.etherware.examples.scenario;

import io.etherware.core.scheduler.FifoScheduler;
import io.etherware.rt.scheduling.CriticalityDeadlinePlacement;
import io.etherware.rt.scheduling.RealtimeScheduler;
import io.etherware.rt.scheduling.RealtimeSchedulerConfig;
import io.etherware.rt.scheduling.ThreadSchedulingRule;

/** The two schedulers the scenarios compare, configured as the paper describes them. Stateless. */
public final class Schedulers {

    private Schedulers() {
    }

    /** The original Etherware: one dispatcher thread at normal priority, first come first served. */
    public static FifoScheduler original() {
        return new FifoScheduler("fifo-dispatcher");
    }

    /**
     * Etherware-RT: the Thread Scheduling Rule of Table II (dispatcher 0 SCHED_OTHER, 1..3
     * SCHED_FIFO 80/70/60) and the Job Placement Rule of Algorithm 1 (HIGH on 1, MIDDLE on 2, LOW
     * on 3, earliest {@code now + period} first).
     */
    public static RealtimeScheduler etherwareRt() {
        return etherwareRt(io.etherware.rt.platform.CpuSet.inherit());
    }

    /**
     * {@link #etherwareRt()} with the JVM's CPUs partitioned ({@code RealtimeSchedulerConfig.realtimeCpus}):
     * its real-time dispatchers, and every real-time thread that asks for inherited CPUs, on
     * {@code realtimeCpus}, every other thread of the JVM elsewhere (inherit: no partition).
     */
    public static RealtimeScheduler etherwareRt(io.etherware.rt.platform.CpuSet realtimeCpus) {
        return new RealtimeScheduler(RealtimeSchedulerConfig.builder()
                .name("rt")
                .threadSchedulingRule(ThreadSchedulingRule.tableII())
                .realtimeCpus(realtimeCpus)
                .placementRule(new CriticalityDeadlinePlacement())
                .build());
    }
}
