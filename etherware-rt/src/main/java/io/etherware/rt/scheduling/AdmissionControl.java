package io.etherware.rt.scheduling;

import io.etherware.core.message.Empty;
import io.etherware.core.message.Message;
import io.etherware.core.message.MessageId;
import io.etherware.core.scheduler.Job;
import java.util.ArrayList;
import java.util.List;
import java.util.Objects;
import org.slf4j.Logger;
import org.slf4j.LoggerFactory;

/**
 * Admission control for declared periodic streams: from each stream's WCET and period, the
 * utilization of the dispatcher the Job Placement Rule puts it on, checked against that
 * dispatcher's policy bound (rate-monotonic {@code n (2^(1/n) - 1)}, EDF 1; see {@link QueuePolicy}
 * for what the bounds leave out). In {@link AdmissionMode#WARN} mode an unschedulable stream is
 * admitted with a warning; in {@link AdmissionMode#REJECT} mode it is refused with an exception.
 *
 * <p>The check is per dispatcher, as the paper leaves schedulability analysis to the application
 * designer: it does not model the interference of higher-priority dispatchers sharing a CPU.
 *
 * <p>Thread-safe; meant for configuration time (declare streams before or while the node runs, not
 * per message).
 */
public final class AdmissionControl {

    private static final Logger LOG = LoggerFactory.getLogger(AdmissionControl.class);
    private static final MessageId PROBE_ID = new MessageId("admission", 0);

    private final JobPlacementRule placementRule;
    private final AdmissionMode mode;
    private final List<List<PeriodicStream>> streamsByDispatcher = new ArrayList<>();

    AdmissionControl(JobPlacementRule placementRule, int dispatcherCount, AdmissionMode mode) {
        this.placementRule = Objects.requireNonNull(placementRule, "placementRule");
        this.mode = Objects.requireNonNull(mode, "mode");
        for (int i = 0; i < dispatcherCount; i++) {
            streamsByDispatcher.add(new ArrayList<>());
        }
    }

    /**
     * What {@link #declare} does with a stream that would break its dispatcher's bound.
     *
     * @return the configured mode
     */
    public AdmissionMode mode() {
        return mode;
    }

    /**
     * Declares a stream and checks its dispatcher's schedulability with it.
     *
     * @param stream the stream; declaring an equal stream again counts it twice
     * @return the dispatcher's load with the stream
     * @throws AdmissionRejectedException in {@link AdmissionMode#REJECT} mode when the dispatcher
     *                                    would exceed its bound; the stream is then not added
     * @throws IllegalStateException      when the placement rule puts the stream on a dispatcher
     *                                    the scheduler does not have
     */
    public synchronized DispatcherLoad declare(PeriodicStream stream) {
        Objects.requireNonNull(stream, "stream");
        int dispatcherId = dispatcherOf(stream);
        var streams = new ArrayList<>(streamsByDispatcher.get(dispatcherId));
        streams.add(stream);
        DispatcherLoad load = load(dispatcherId, streams);
        if (!load.isSchedulable()) {
            if (mode == AdmissionMode.REJECT) {
                throw new AdmissionRejectedException(stream, load);
            }
            LOG.warn("stream to {} ({}, period {} ns, wcet {} ns) admitted, but {}", stream.target(),
                    stream.qos().criticality(), stream.qos().periodNs(), stream.qos().wcetNs(), load);
        }
        streamsByDispatcher.get(dispatcherId).add(stream);
        return load;
    }

    /**
     * Removes a declared stream, one occurrence of it.
     *
     * @param stream a stream declared before
     * @return whether it was declared (and is now removed)
     */
    public synchronized boolean withdraw(PeriodicStream stream) {
        return streamsByDispatcher.get(dispatcherOf(stream)).remove(stream);
    }

    /**
     * Every dispatcher's declared load.
     *
     * @return one load per dispatcher, in dispatcher order, including those without streams; a new
     *         list the caller owns
     */
    public synchronized List<DispatcherLoad> loads() {
        var loads = new ArrayList<DispatcherLoad>();
        for (int id = 0; id < streamsByDispatcher.size(); id++) {
            loads.add(load(id, streamsByDispatcher.get(id)));
        }
        return loads;
    }

    /**
     * The dispatcher the placement rule puts a stream's messages on, found by placing a probe
     * message with the stream's target and QoS at time 0.
     *
     * @param stream the stream
     * @return the dispatcher id
     * @throws IllegalStateException when the rule puts it on a dispatcher the scheduler does not have
     */
    public int dispatcherOf(PeriodicStream stream) {
        Message probe = new Message(stream.target(), null, 0L, stream.qos(), Empty.INSTANCE, PROBE_ID, null);
        int dispatcherId = placementRule.place(new Job(probe, stream.target().toString(), stream.target(), 0, 0L), 0L)
                .dispatcherId();
        if (dispatcherId >= streamsByDispatcher.size()) {
            throw new IllegalStateException("placement rule " + placementRule.name() + " put a stream to "
                    + stream.target() + " on dispatcher " + dispatcherId + ", but there are only "
                    + streamsByDispatcher.size());
        }
        return dispatcherId;
    }

    private DispatcherLoad load(int dispatcherId, List<PeriodicStream> streams) {
        double utilization = 0;
        for (PeriodicStream stream : streams) {
            utilization += stream.utilization();
        }
        QueuePolicy policy = placementRule.queuePolicy(dispatcherId);
        return new DispatcherLoad(dispatcherId, policy, streams.size(), utilization,
                policy.utilizationBound(streams.size()));
    }
}
