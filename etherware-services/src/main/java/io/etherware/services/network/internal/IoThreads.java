package io.etherware.services.network.internal;

import io.etherware.core.kernel.Kernel;
import io.etherware.rt.platform.CpuSet;
import io.etherware.rt.platform.Platform;
import io.etherware.rt.platform.ThreadPolicy;
import io.etherware.rt.scheduling.RealtimeScheduler;
import io.etherware.rt.scheduling.ThreadSchedulingRule;
import io.etherware.services.network.NetworkConfig;

/**
 * The OS policy and CPUs of one lane's reader and writer threads: configured, or by default, with
 * the node's {@link RealtimeScheduler}, lane 0 (HIGH and MIDDLE messages) one real-time level above
 * its highest dispatcher and lane 1 (LOW and NONE) one level above its lowest real-time one, so a
 * thread never carries messages at a priority below work less critical than theirs, nor above work
 * more critical (DESIGN decision 13); ordinary threads with another scheduler.
 *
 * @param policy what the threads ask for
 * @param cpus   where they run
 */
record IoThreads(ThreadPolicy policy, CpuSet cpus) {

    static IoThreads of(Kernel kernel, NetworkConfig config, int lane) {
        ThreadPolicy policy = lane == 0 ? config.threadPolicy() : config.bulkThreadPolicy();
        if (policy == null) {
            ThreadSchedulingRule rule = kernel.scheduler() instanceof RealtimeScheduler realtime
                    ? realtime.config().threadSchedulingRule() : null;
            policy = rule == null ? ThreadPolicy.NON_REALTIME : lane == 0 ? rule.above(1) : rule.aboveLowest(1);
        }
        return new IoThreads(policy, config.cpus());
    }

    /**
     * Gives the calling reader or writer thread its policy and CPUs, once its connection is
     * established (a handshake never runs at real-time priority); a refusal is warned once.
     */
    void configureCurrent() {
        if (policy.isRealtime() || !cpus.equals(CpuSet.inherit())) {
            Platform.current().configureCurrentThread(policy, cpus);
        }
    }
}
