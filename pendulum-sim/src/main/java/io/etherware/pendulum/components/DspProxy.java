package io.etherware.pendulum.components;

import io.etherware.core.component.Component;
import io.etherware.core.component.ComponentContext;
import io.etherware.core.component.ComponentState;
import io.etherware.core.message.Contents;
import io.etherware.core.message.ContentsTypes;
import io.etherware.core.message.Message;
import io.etherware.core.message.Profile;
import io.etherware.pendulum.serial.Angles;
import io.etherware.pendulum.serial.BoardStatus;
import io.etherware.pendulum.serial.DspClient;
import io.etherware.pendulum.serial.DspException;
import io.etherware.pendulum.serial.DspTimeoutException;
import io.etherware.pendulum.serial.TorqueAck;
import java.util.Objects;
import java.util.function.Supplier;
import org.slf4j.Logger;
import org.slf4j.LoggerFactory;

/**
 * The paper's DSPProxy (Section VI-A, Fig. 8): the component on the node that owns the serial link
 * to the DSP board. It serves {@link ReadAngles} requests with an {@link AnglesReading} (or a
 * {@link DspFault}), forwards {@link SetTorque} commands and answers {@link StatusRequest}s, each
 * through one synchronous exchange of its {@link DspClient}.
 *
 * <p><b>Threading and timing.</b> Called by the kernel one message at a time, on its dispatcher.
 * Unlike most components it blocks there: each exchange waits for the board's reply, about 2.7 ms
 * for a reading and 2.0 ms for a command at 115200 baud (wire time plus up to one 0.5 ms board
 * cycle), up to the client's timeout times its attempts when frames are lost. That wait is the
 * serial round trip of the real plant and is part of the control loop's budget, as in the paper:
 * of a 15 ms period about 4.7 ms are serial time; on a node with several dispatchers, place the proxy so it does not delay unrelated
 * components. Serial failures are answered and counted, never thrown, so they do not trigger a
 * restart.
 *
 * <p><b>Ownership.</b> The proxy uses the client but does not close its link: a restart or an
 * upgrade makes a new instance on the same client (see {@link #factory}), and the application
 * that opened the link closes it after the node. The client is not thread-safe; the kernel's
 * one-message-at-a-time rule is what makes sharing it between successive instances safe.
 */
public final class DspProxy implements Component {

    /** The proxy's usual profile, {@code dsp-proxy[pendulum=1]}. */
    public static final Profile DEFAULT_PROFILE = Profile.of("dsp-proxy", "pendulum", "1");

    private static final Logger LOG = LoggerFactory.getLogger(DspProxy.class);

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

    private final DspClient client;
    private long angleReads;
    private long torqueCommands;
    private long statusReads;
    private long timeouts;
    private long linkErrors;
    private long saturatedCommands;
    private long watchdogRecoveries;
    private long unexpectedMessages;
    private double lastTorqueNm;

    /**
     * A proxy serving the board behind a client.
     *
     * @param client the board's client; the proxy does not close its link
     * @throws NullPointerException when {@code client} is null
     */
    public DspProxy(DspClient client) {
        this.client = Objects.requireNonNull(client, "client");
    }

    /**
     * A factory for {@code EtherwareNode.add}: every instance (restarts too) uses {@code client}.
     *
     * @param client the board's client, shared by the successive instances
     * @return the factory
     * @throws NullPointerException when {@code client} is null
     */
    public static Supplier<DspProxy> factory(DspClient client) {
        Objects.requireNonNull(client, "client");
        return () -> new DspProxy(client);
    }

    /**
     * Serves one message with one synchronous serial exchange, on the proxy's dispatcher; blocks
     * for the exchange (see the type's timing note). Replies only to a message with a sender.
     * Serial failures are counted and never thrown: a failed reading is answered with a
     * {@link DspFault}, a failed status read is reported inside the {@link DspProxyStatus}, a lost
     * {@link SetTorque} is only counted.
     *
     * @param message a {@link ReadAngles}, {@link SetTorque} or {@link StatusRequest}; any other
     *                contents are counted and a request for them is answered with a
     *                {@link DspFault} of kind {@code UNSUPPORTED}
     * @param context the proxy's context, to reply with
     */
    @Override
    public void onMessage(Message message, ComponentContext context) {
        switch (message.contents()) {
            case ReadAngles request -> readAngles(message, request, context);
            case SetTorque command -> setTorque(command);
            case StatusRequest request -> status(message, request, context);
            default -> unexpected(message, context);
        }
    }

    private void readAngles(Message message, ReadAngles request, ComponentContext context) {
        DspFault fault;
        try {
            Angles angles = client.readAngles();
            angleReads++;
            replyIfAsked(message, context, new AnglesReading(request.cycle(), angles.sequence(),
                    angles.encoder1Counts(), angles.encoder2Counts(), angles.dspTimeUs(),
                    angles.theta1Rad(), angles.theta2Rad()));
            return;
        } catch (DspTimeoutException e) {
            timeouts++;
            fault = new DspFault(request.cycle(), DspFault.Kind.TIMEOUT, e.getMessage());
        } catch (DspException e) {
            linkErrors++;
            fault = new DspFault(request.cycle(), DspFault.Kind.LINK_ERROR, e.getMessage());
        }
        LOG.debug("{}: cycle {} read failed: {}", context.self(), request.cycle(), fault.detail());
        replyIfAsked(message, context, fault);
    }

    private void setTorque(SetTorque command) {
        try {
            TorqueAck ack = client.setTorque(command.torqueNm());
            torqueCommands++;
            lastTorqueNm = command.torqueNm();
            if (ack.saturated()) {
                saturatedCommands++;
            }
            if (ack.watchdogWasTripped()) {
                watchdogRecoveries++;
            }
        } catch (DspTimeoutException e) {
            // The board keeps the last torque until its watchdog cuts the motor (design decision 10).
            timeouts++;
            LOG.debug("cycle {}: torque command lost: {}", command.cycle(), e.getMessage());
        } catch (DspException e) {
            linkErrors++;
            LOG.debug("cycle {}: torque command failed: {}", command.cycle(), e.getMessage());
        }
    }

    private void status(Message message, StatusRequest request, ComponentContext context) {
        BoardStatus board = null;
        String boardError = null;
        if (request.includeBoard()) {
            try {
                board = client.readStatus();
            } catch (DspTimeoutException e) {
                timeouts++;
                boardError = e.getMessage();
            } catch (DspException e) {
                linkErrors++;
                boardError = e.getMessage();
            }
        }
        statusReads++;
        replyIfAsked(message, context, new DspProxyStatus(counters(), client.counters(), board, boardError));
    }

    private void unexpected(Message message, ComponentContext context) {
        unexpectedMessages++;
        String type = message.contents().getClass().getSimpleName();
        LOG.debug("{}: ignoring message {} from '{}' with contents {}", context.self(), message.messageId(),
                message.sender(), type);
        // Answer a request so its sender fails fast instead of timing out; never answer a reply
        // or a notice (that could ping-pong between two components).
        if (!message.isReply()) {
            replyIfAsked(message, context, new DspFault(0, DspFault.Kind.UNSUPPORTED,
                    "dsp-proxy does not serve contents " + type
                            + "; it serves ReadAngles, SetTorque and StatusRequest"));
        }
    }

    private static void replyIfAsked(Message message, ComponentContext context, Contents contents) {
        if (message.hasSender()) {
            context.reply(message, contents);
        }
    }

    /**
     * The counters now. Call on the proxy's dispatcher (or read them from a {@link StatusRequest}).
     *
     * @return a new snapshot of the counters
     */
    public DspProxyCounters counters() {
        return new DspProxyCounters(angleReads, torqueCommands, statusReads, timeouts, linkErrors,
                saturatedCommands, watchdogRecoveries, unexpectedMessages, lastTorqueNm);
    }

    /**
     * The proxy's state: its counters, so a restart keeps counting.
     *
     * @return the {@link DspProxyCounters} now
     */
    @Override
    public ComponentState snapshot() {
        return counters();
    }

    /**
     * Continues counting from a previous instance's counters.
     *
     * @param state a {@link DspProxyCounters}
     * @throws IllegalArgumentException when {@code state} is not a {@link DspProxyCounters}
     */
    @Override
    public void restore(ComponentState state) {
        if (!(state instanceof DspProxyCounters counters)) {
            throw new IllegalArgumentException("a DspProxy restores DspProxyCounters, not "
                    + (state == null ? "null" : state.getClass().getName()));
        }
        angleReads = counters.angleReads();
        torqueCommands = counters.torqueCommands();
        statusReads = counters.statusReads();
        timeouts = counters.timeouts();
        linkErrors = counters.linkErrors();
        saturatedCommands = counters.saturatedCommands();
        watchdogRecoveries = counters.watchdogRecoveries();
        unexpectedMessages = counters.unexpectedMessages();
        lastTorqueNm = counters.lastTorqueNm();
    }
}
