package io.etherware.services.network.internal;

import io.etherware.core.kernel.EtherwareNode;
import io.etherware.core.kernel.Kernel;
import io.etherware.rt.platform.CpuSet;
import io.etherware.rt.platform.Platform;
import io.etherware.rt.platform.ThreadPolicy;
import io.etherware.rt.scheduling.RealtimeScheduler;
import io.etherware.services.network.NetworkConfig;

/**
 * The OS policy and CPUs of the connections' reader and writer threads: configured, or by default
 * one real-time level above the highest dispatcher of the node's {@link RealtimeScheduler} (a
 * thread that carries HIGH messages must not wait for LOW work; DESIGN decision 13), ordinary
 * threads with another scheduler.
 *
 * @param policy what the threads ask for
 * @param cpus   where they run
 */
record IoThreads(ThreadPolicy policy, CpuSet cpus) {

    static IoThreads of(Kernel kernel, NetworkConfig config) {
        ThreadPolicy policy = config.threadPolicy();
        if (policy == null) {
            policy = kernel instanceof EtherwareNode node && node.scheduler() instanceof RealtimeScheduler realtime
                    ? realtime.config().threadSchedulingRule().above(1) : ThreadPolicy.NON_REALTIME;
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
