package io.etherware.pendulum.components;

import io.etherware.core.component.Component;
import io.etherware.core.component.ComponentContext;
import io.etherware.core.component.ComponentState;
import io.etherware.core.message.ContentsTypes;
import io.etherware.core.message.Message;
import io.etherware.core.message.Profile;
import io.etherware.core.message.QoS;
import io.etherware.core.message.Tick;
import io.etherware.pendulum.control.BalanceControl;
import io.etherware.pendulum.control.BalanceControlState;
import io.etherware.pendulum.control.GainSet;
import io.etherware.pendulum.control.VelocityEstimatorState;
import java.util.Objects;
import java.util.function.Supplier;
import org.slf4j.Logger;
import org.slf4j.LoggerFactory;

/**
 * The paper's balancing controller as an Etherware component (Section VI-A and VI-C, Fig. 10).
 * Each {@link Tick} starts a cycle: it requests the joint angles from the {@link DspProxy}
 * ({@link ReadAngles}, asynchronously, with the Tick's QoS and a timeout shorter than the period),
 * and when the {@link AnglesReading} comes back it computes {@code u = −K (x − x0)} with a
 * {@link BalanceControl} and sends {@link SetTorque}. It only ever sees the board's encoder
 * counts and time stamps, never the simulation (design decision 9).
 *
 * <p>A failed reading (timeout, {@link DspFault}, undeliverable) skips the cycle: no torque is
 * sent and the board holds the last one, until its watchdog cuts the motor after 100 ms. A Tick
 * that comes while the previous cycle still waits abandons that cycle (counted in {@code abandonedCycles}; its
 * reading, if it comes, is dropped as late), so a slow link never makes cycles pile up.
 *
 * <p><b>State.</b> {@link #snapshot()} returns a {@link ControllerState}: the estimator's memory,
 * the gain set, θ1r and the counters. A new instance built with another {@link GainSet} and given
 * that state by {@link #restore} continues the same loop with the new gains: that is the upgrade
 * of Section VI-C1 ({@code node.swap(profile, PendulumController.factory(config, v2, listener))}).
 * The restored θ1r and counters win over the new instance's configuration; its gains win over the
 * state's.
 *
 * <p><b>Threading.</b> The kernel calls it one message at a time; the reading's continuation runs
 * in the same exclusive turn (the kernel completes a component's request future as a job of that
 * component), so no field needs synchronization. Only {@link #lastCycle()} may be read from other
 * threads. Per cycle it allocates a few small records and does not block.
 */
public final class PendulumController implements Component {

    /** The controller's usual profile, {@code controller[pendulum=1]}. */
    public static final Profile DEFAULT_PROFILE = Profile.of("controller", "pendulum", "1");

    private static final Logger LOG = LoggerFactory.getLogger(PendulumController.class);

    /**
     * Registers the pendulum's contents ({@link PendulumContents#register}) in {@code types}; the
     * management service calls this on a node's registry when it loads this class for an upgrade
     * or a migration.
     *
     * @param types the node's registry
     */
    public static void registerContents(ContentsTypes types) {
        PendulumContents.register(types);
    }

    private final ControllerConfig config;
    private final GainSet gains;
    private final ControlListener listener;
    private final BalanceControl control;
    private ComponentContext context;
    /** Set when the kernel stops this instance; a reading that comes afterwards is its successor's business. */
    private boolean stopped;
    private boolean warnedTimeoutVsPeriod;
    private boolean warnedListener;
    private long ignoredMessages;

    private long ticks;
    private long missedReplies;
    private long lateReplies;
    private long abandonedCycles;
    private long skippedTicks;
    private long lastTickSequence = -1;
    private long pendingCycle = -1;
    private long pendingReleaseNs;
    private long pendingStartNs;
    private double lastTorqueNm;
    private volatile ControlCycle lastCycle;

    /**
     * A controller.
     *
     * @param config where the proxy is, the reply timeout, θ1r and limits
     * @param gains the gain set this instance computes with (V1 or V2)
     * @param listener told about every cycle, on the controller's dispatcher
     */
    public PendulumController(ControllerConfig config, GainSet gains, ControlListener listener) {
        this.config = Objects.requireNonNull(config, "config");
        this.gains = Objects.requireNonNull(gains, "gains");
        this.listener = Objects.requireNonNull(listener, "listener (use ControlListener.NONE)");
        this.control = new BalanceControl(gains, config.theta1ReferenceRad(), config.maxTorqueNm(),
                config.filterTimeConstantNs());
    }

    /**
     * A factory for {@code EtherwareNode.add} and {@code swap}: every instance computes with
     * {@code gains}; restarts and upgrades hand it the previous instance's state.
     *
     * @param config   where the proxy is, the reply timeout, θ1r and limits
     * @param gains    the gain set every instance computes with (V1 or V2)
     * @param listener told about every cycle, on the controller's dispatcher;
     *                 {@link ControlListener#NONE} for none
     * @return the factory
     * @throws NullPointerException when an argument is null
     */
    public static Supplier<PendulumController> factory(ControllerConfig config, GainSet gains,
            ControlListener listener) {
        Objects.requireNonNull(config, "config");
        Objects.requireNonNull(gains, "gains");
        Objects.requireNonNull(listener, "listener");
        return () -> new PendulumController(config, gains, listener);
    }

    /**
     * Keeps the context for the cycles' requests and commands.
     *
     * @param componentContext this controller's context
     */
    @Override
    public void onStart(ComponentContext componentContext) {
        this.context = componentContext;
    }

    /**
     * Starts a cycle on a {@link Tick}: abandons a cycle still waiting, then requests the angles
     * with the Tick's QoS. Does not block; the torque is computed when the reading comes. Other
     * messages are counted and logged, the first at WARN.
     *
     * @param message          a message; only a {@link Tick} starts a cycle
     * @param componentContext this controller's context
     */
    @Override
    public void onMessage(Message message, ComponentContext componentContext) {
        if (message.contents() instanceof Tick tick) {
            onTick(message, tick);
        } else {
            // An undeliverable notice for a SetTorque says the proxy is gone; the next reading fails
            // and is counted. Anything else is not for us.
            ignoredMessages++;
            if (ignoredMessages == 1) {
                LOG.warn("{}: ignoring message {} with contents {} (further ones at debug level)",
                        context.self(), message.messageId(), message.contents());
            } else {
                LOG.debug("{}: ignoring message {} with contents {}", context.self(), message.messageId(),
                        message.contents());
            }
        }
    }

    private void onTick(Message message, Tick tick) {
        long startNs = context.clock().nanoTime();
        ticks++;
        long sequence = tick.sequence();
        if (lastTickSequence >= 0 && sequence > lastTickSequence + 1) {
            skippedTicks += sequence - lastTickSequence - 1;
        }
        lastTickSequence = sequence;
        if (pendingCycle >= 0) {
            abandonedCycles++;
        }
        warnIfTimeoutExceedsPeriod(tick);

        pendingCycle = sequence;
        pendingReleaseNs = tick.releaseNs();
        pendingStartNs = startNs;
        QoS qos = message.qos();
        context.request(config.dspProxy(), new ReadAngles(sequence), qos, config.replyTimeoutNs())
                .whenComplete((reply, failure) -> onReadout(sequence, qos, reply, failure));
    }

    /** The reading's outcome, in this component's turn (see the type's threading note). */
    private void onReadout(long cycle, QoS qos, Message reply, Throwable failure) {
        if (stopped) {
            return; // replaced by an upgrade or a restart: the successor counts this cycle as abandoned
        }
        try {
            long nowNs = context.clock().nanoTime();
            if (cycle != pendingCycle) {
                lateReplies++;
                return;
            }
            pendingCycle = -1;
            if (failure != null || !(reply.contents() instanceof AnglesReading reading)) {
                missedReplies++;
                LOG.debug("{}: cycle {} missed its reading: {}", context.self(), cycle,
                        failure != null ? failure.toString() : reply.contents());
                publish(ControlCycle.missed(cycle, pendingReleaseNs, pendingStartNs, nowNs, gains.version()));
                return;
            }
            double torqueNm = control.update(reading.theta1Rad(), reading.theta2Rad(), reading.dspTimeUs());
            context.send(config.dspProxy(), new SetTorque(cycle, torqueNm), qos);
            lastTorqueNm = torqueNm;
            VelocityEstimatorState estimate = control.state().estimator();
            publish(new ControlCycle(cycle, pendingReleaseNs, pendingStartNs, nowNs,
                    ControlCycle.Outcome.COMMANDED, reading.theta1Rad(), reading.theta2Rad(),
                    estimate.theta1RateRadPerS(), estimate.theta2RateRadPerS(), reading.dspTimeUs(),
                    torqueNm, gains.version()));
        } catch (RuntimeException e) {
            // An exception in a future's continuation would vanish into the derived future, out of
            // the kernel's supervision: say it loudly. The next Tick starts afresh.
            LOG.error("{}: cycle {} failed after its reading", context.self(), cycle, e);
        }
    }

    private void publish(ControlCycle cycle) {
        lastCycle = cycle;
        try {
            listener.onCycle(cycle);
        } catch (RuntimeException e) {
            if (!warnedListener) {
                warnedListener = true;
                LOG.warn("{}: the control listener threw; ignored (reported once)", context.self(), e);
            }
        }
    }

    private void warnIfTimeoutExceedsPeriod(Tick tick) {
        if (!warnedTimeoutVsPeriod && tick.periodNs() > 0 && config.replyTimeoutNs() >= tick.periodNs()) {
            warnedTimeoutVsPeriod = true;
            LOG.warn("{}: replyTimeoutNs={} is not below the Tick period {} ns: a lost reading is noticed only"
                    + " after the next release, which abandons its cycle",
                    context.self(), config.replyTimeoutNs(), tick.periodNs());
        }
    }

    /**
     * Stops this instance: a reading that comes afterwards is ignored (the successor counts its
     * cycle as abandoned).
     */
    @Override
    public void onStop() {
        stopped = true;
    }

    /**
     * The loop's state for a restart, an upgrade or a migration.
     *
     * @return a new {@link ControllerState}: control memory, counters and the pending cycle
     */
    @Override
    public ControllerState snapshot() {
        return new ControllerState(control.state(), ticks, missedReplies, lateReplies, abandonedCycles, skippedTicks,
                lastTickSequence, pendingCycle, lastTorqueNm);
    }

    /**
     * Continues from a previous instance's {@link ControllerState}: the estimator's memory, θ1r
     * and the counters carry over; this instance's gain set replaces the state's.
     *
     * @param state the previous instance's {@link ControllerState}
     * @throws IllegalArgumentException if the state is not a {@link ControllerState} of a known
     *                                  schema version (an upgrade is then rolled back)
     */
    @Override
    public void restore(ComponentState state) {
        if (!(state instanceof ControllerState previous)) {
            throw new IllegalArgumentException("a PendulumController restores a ControllerState, not "
                    + (state == null ? "null" : state.getClass().getName()));
        }
        if (previous.schemaVersion() != ControllerState.SCHEMA_VERSION) {
            throw new IllegalArgumentException("ControllerState schemaVersion=" + previous.schemaVersion()
                    + " is not supported; this controller reads version " + ControllerState.SCHEMA_VERSION);
        }
        BalanceControlState memory = previous.control();
        control.restore(memory);
        control.useGains(gains);
        ticks = previous.ticks();
        missedReplies = previous.missedReplies();
        lateReplies = previous.lateReplies();
        abandonedCycles = previous.abandonedCycles();
        skippedTicks = previous.skippedTicks();
        lastTickSequence = previous.lastTickSequence();
        pendingCycle = previous.pendingCycle();
        lastTorqueNm = previous.lastTorqueNm();
        // Debug, and only then compared: this runs inside the swap's pause, where on two loaded
        // cores a node's first log line at info cost about 5 ms (the appender's first use loads and
        // runs its classes) and a record's first equals 2-4 ms (its bootstrap); the management
        // service reports the upgrade once the new logic has begun.
        if (LOG.isDebugEnabled() && !memory.gains().equals(gains)) {
            LOG.debug("controller continues after {} cycles with gains {} (v{}) instead of {} (v{})",
                    memory.cycles(), gains.name(), gains.version(), memory.gains().name(),
                    memory.gains().version());
        }
    }

    /**
     * The gain set this instance computes with.
     *
     * @return the gain set given at construction, whatever a restored state held
     */
    public GainSet gains() {
        return gains;
    }

    /**
     * This instance's settings.
     *
     * @return the settings given at construction
     */
    public ControllerConfig config() {
        return config;
    }

    /**
     * The last cycle this instance completed or missed; readable from any thread.
     *
     * @return the cycle, or null before the first
     */
    public ControlCycle lastCycle() {
        return lastCycle;
    }
}
