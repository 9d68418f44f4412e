package io.etherware.core.kernel.internal;

import io.etherware.core.kernel.Kernel;
import io.etherware.core.kernel.OrderMarker;
import io.etherware.core.kernel.RemoteRoute;
import io.etherware.core.kernel.RequestFailed;
import io.etherware.core.kernel.Undeliverable;
import io.etherware.core.message.Contents;
import io.etherware.core.message.Criticality;
import io.etherware.core.message.Message;
import io.etherware.core.message.MessageId;
import io.etherware.core.message.Origin;
import io.etherware.core.message.Profile;
import io.etherware.core.message.QoS;
import io.etherware.core.message.Tick;
import io.etherware.core.scheduler.Job;
import io.etherware.core.scheduler.Scheduler;
import io.etherware.core.time.NodeClock;
import java.util.Set;
import java.util.concurrent.ConcurrentHashMap;
import java.util.concurrent.atomic.AtomicLong;
import java.util.concurrent.atomic.LongAdder;
import java.util.function.BooleanSupplier;
import java.util.function.Consumer;
import java.util.function.Supplier;
import org.slf4j.Logger;
import org.slf4j.LoggerFactory;

/**
 * The kernel's delivery of a message whose destination is resolved: as a job of a local component
 * (made and submitted to the scheduler), along a route to another node, or back to its sender as
 * undeliverable; and of a message that reached a component that no longer runs. Also delivers
 * request outcomes to requesting components and counts the jobs, the undeliverable messages, the
 * discarded jobs and the queued bytes from each neighbour node.
 *
 * <p>Owned by {@link KernelCore}, which resolves profiles and hands messages here.
 *
 * <p>Thread-safety: every method may be called from any thread and takes no lock; the per-message
 * path allocates nothing in steady state under a scheduler that recycles its jobs, as the
 * real-time one does (jobs come from the sending thread's pool, see {@link Job#pooled}); under the
 * FIFO scheduler each job is new.
 */
final class Delivery {

    /** Logs as the kernel: these are the kernel's messages. */
    private static final Logger log = LoggerFactory.getLogger(Kernel.class);
    /**
     * Added to the sequence of a penned job (see {@link ArrivalPen}): under a scheduler whose
     * urgency is the sequence, it then sorts after the jobs of the same urgency not penned. Far
     * above any sequence a node reaches.
     */
    static final long PEN_OFFSET = 1L << 62;
    private static final int MAX_ROUTE_REFUSALS_LOGGED = 64;

    private final String nodeId;
    private final Profile nodeProfile;
    private final NodeClock clock;
    private final Scheduler scheduler;
    /** The kernel's send, through which an undeliverable notice goes to the sender. */
    private final Consumer<Message> send;
    private final Supplier<MessageId> newMessageId;
    /** Whether the node is closing or closed. */
    private final BooleanSupplier closing;
    private final AtomicLong jobSequence = new AtomicLong();
    /** Bytes of queued messages from the network, by the node they came through. */
    private final ConcurrentHashMap<String, LongAdder> inboundBytes = new ConcurrentHashMap<>();
    private final LongAdder undeliverable = new LongAdder();
    /** Destinations whose route refused a message, logged once each (at most {@link #MAX_ROUTE_REFUSALS_LOGGED}). */
    private final Set<Profile> routeRefusalsLogged = ConcurrentHashMap.newKeySet();
    private final LongAdder discarded = new LongAdder();

    /**
     * @param send         the kernel's send (taps, reply correlation, resolution), for notices
     * @param newMessageId the kernel's message ids, for notices
     * @param closing      whether the node is closing or closed
     */
    Delivery(String nodeId, Profile nodeProfile, NodeClock clock, Scheduler scheduler, Consumer<Message> send,
             Supplier<MessageId> newMessageId, BooleanSupplier closing) {
        this.nodeId = nodeId;
        this.nodeProfile = nodeProfile;
        this.clock = clock;
        this.scheduler = scheduler;
        this.send = send;
        this.newMessageId = newMessageId;
        this.closing = closing;
    }

    /** Makes {@code message} a job of {@code shell} and submits it (or forwards it, if it relocated). */
    void enqueue(Message message, LocalShell shell) {
        long nowNs = clock.nanoTime();
        long releaseNs = nowNs;
        // A local Tick is released at its scheduled time, so start latency counts from there.
        if (message.contents() instanceof Tick tick && tick.releaseNs() <= nowNs
                && nodeId.equals(message.messageId().nodeId())) {
            releaseNs = tick.releaseNs();
        } else if (message.origin() != null) {
            // From another node: released when it was made there (its time stamp, which NetworkTime
            // translated into this node's clock), so its deadline is absolute across nodes and the
            // time on the wire counts (DESIGN decision 12); one that arrives late is a miss.
            long ageNs = clock.epochNanos() - message.timeStamp();
            if (ageNs > 0) {
                releaseNs = nowNs - ageNs;
            }
        }
        if (!shell.enterQueue()) {
            deliverRemote(message, shell.forwardRoute()); // relocated, and nothing of it is queued here
            return;
        }
        if (message.contents() instanceof OrderMarker && (shell.pen() == null || shell.pen().isAdmitted())) {
            // The component is hosted here: whatever its sender sent it before the marker is
            // queued here already, and the kernel keeps its order from here on, through holds
            // and moves, before anything the sender sends later. So the marker makes no job.
            // (One that reaches a component still arriving waits, as a job, for the admission:
            // this node may have relayed earlier ones to the source, which forwards them back.)
            shell.leaveQueue();
            answerMarker(message);
            ArrivalPen pen = shell.pen();
            if (pen != null && pen.isArrival(message)) {
                pen.arrived();
            }
            return;
        }
        shell.countQueued(message, +1);
        long sequence = jobSequence.getAndIncrement();
        boolean penned = shell.pens(message);
        if (penned) {
            sequence += PEN_OFFSET;
        }
        Job job = Job.pooled(message, shell.name(), shell, sequence, releaseNs);
        ArrivalPen pen = shell.pen();
        if (penned && pen.defer(job)) {
            return; // submitted at the admission, after every forwarded job
        }
        submit(job, shell);
        if (pen != null && pen.isArrival(message)) {
            pen.arrived(); // after the submission: the admission's hand-over queues behind it
        }
    }

    /** Submits a counted job of {@code shell}; if the scheduler refuses it, it is discarded. */
    void submit(Job job, LocalShell shell) {
        if (!scheduler.submit(job)) {
            shell.leaveQueue();
            shell.countQueued(job.message(), -1);
            discard(job);
        }
    }

    /**
     * Counts the bytes of a message from the network while it is a queued job of a component:
     * added when the job is made, removed when it leaves the component's queue count (ran,
     * forwarded, or refused), the same points that keep {@link LocalShell}'s queue count exact.
     */
    void countInbound(Message message, int sign) {
        Origin origin = message.origin();
        if (origin != null && origin.wireBytes() > 0) {
            inboundBytes.computeIfAbsent(origin.viaNodeId(), id -> new LongAdder()).add((long) sign * origin.wireBytes());
        }
    }

    /** Bytes of the queued messages that came through node {@code viaNodeId}. */
    long queuedBytesFrom(String viaNodeId) {
        LongAdder bytes = inboundBytes.get(viaNodeId);
        return bytes == null ? 0 : bytes.sum();
    }

    /** Hands a message to a route; a refusal makes it undeliverable. */
    void deliverRemote(Message message, RemoteRoute route) {
        try {
            route.deliver(message);
        } catch (RuntimeException e) {
            String reason = "the route to '" + message.profile() + "' refused it: " + e;
            // A refusal is usually a mistake in the application (a contents type not registered on
            // this node, a record the codec cannot read): say so once per destination where it shows,
            // not only to the sender.
            if (routeRefusalsLogged.size() < MAX_ROUTE_REFUSALS_LOGGED && routeRefusalsLogged.add(message.profile())) {
                log.warn("node {}: {} (logged once per destination; later ones go to the sender only)", nodeId,
                        reason);
            }
            undeliverable(message, reason);
        }
    }

    /** Hands a request's outcome to its requester. */
    void deliverOutcome(PendingRequest entry) {
        LocalShell requester = entry.requester;
        if (requester == null) {
            entry.settle();
            return;
        }
        Message carrier = entry.outcomeMessage();
        Job job = Job.pooled(carrier, requester.name(), entry, jobSequence.getAndIncrement(), clock.nanoTime());
        if (!scheduler.submit(job)) {
            discard(job);
        }
    }

    /** Submits a job again (a reserved one, see {@link ComponentGate}); false if refused. */
    boolean resubmit(Job job) {
        return scheduler.submit(job);
    }

    /** Counts a job the node will not run because it is closing; settles request outcomes. */
    void discard(Job job) {
        discarded.increment();
        if (job.target() instanceof PendingRequest entry) {
            entry.settle();
        }
    }

    /** A message reached a component that does not run (owner thread of {@code shell}). */
    void notRunning(LocalShell shell, Message message) {
        if (closing.getAsBoolean()) {
            discarded.increment();
        } else if (shell.isRemoved()) {
            send.accept(message); // re-resolve: the profile may live elsewhere now (migration)
        } else {
            undeliverable(message, "component '" + shell.name() + "' is " + shell.state());
        }
    }

    /** Counts an undeliverable message and tells its sender, if there is one to tell. */
    void undeliverable(Message message, String reason) {
        Contents contents = message.contents();
        if (contents instanceof OrderMarker) {
            answerMarker(message); // no component to put its sender's later messages behind
            return;
        }
        undeliverable.increment();
        if (message.sender() == null || contents instanceof Undeliverable || contents instanceof RequestFailed) {
            // Nobody to tell, or a notice about a notice (which could loop): the log is the notice.
            log.warn("node {}: message {} to '{}' is undeliverable: {}", nodeId, message.messageId(), message.profile(),
                    reason);
            return;
        }
        log.debug("node {}: message {} to '{}' is undeliverable: {}", nodeId, message.messageId(), message.profile(),
                reason);
        send.accept(new Message(message.sender(), nodeProfile, clock.epochNanos(), message.qos(),
                new Undeliverable(message.profile().toString(), message.messageId().toString(), reason),
                newMessageId.get(), message.messageId()));
    }

    /**
     * An {@link OrderMarker} reached the node hosting its component (or no component at all):
     * answers the node it came from, by the connection's word, never a profile the message names,
     * to that node's profile, as a message of its own (not a reply: it completes no request). One
     * that claims to come from this node is not answered: nothing here sends one.
     */
    void answerMarker(Message marker) {
        Origin origin = marker.origin();
        if (origin == null || origin.nodeId().equals(nodeId)) {
            return;
        }
        try {
            send.accept(new Message(Profile.of(nodeProfile.role(), "id", origin.nodeId()), nodeProfile,
                    clock.epochNanos(), QoS.of(Criticality.HIGH), marker.contents(), newMessageId.get(), null));
        } catch (RuntimeException e) {
            log.debug("node {}: could not answer order marker {} of node '{}': {}", nodeId, marker.messageId(),
                    origin.nodeId(), e.toString());
        }
    }

    /** Jobs made so far, for the node's stats. */
    long jobCount() {
        return jobSequence.get();
    }

    long undeliverableCount() {
        return undeliverable.sum();
    }

    long discardedCount() {
        return discarded.sum();
    }
}
