package io.etherware.pendulum.components;

import io.etherware.core.message.Profile;
import io.etherware.core.time.Durations;
import io.etherware.pendulum.control.VelocityEstimator;
import io.etherware.pendulum.dsp.DspBoardConfig;
import java.time.Duration;
import java.util.Objects;

/**
 * Settings of a {@link PendulumController}, apart from its gain set (which an upgrade changes).
 * Immutable; validated at construction, messages name the field and the value.
 *
 * @param dspProxy where the controller sends {@link ReadAngles} and {@link SetTorque}: the proxy's
 *     exact profile or a query that matches it
 * @param replyTimeoutNs how long a cycle waits for its reading; keep it below the Tick period so
 *     a lost reading is known before the next release (otherwise the next Tick abandons the cycle
 *     and counts it as abandoned). The kernel times requests out on the wall clock.
 * @param theta1ReferenceRad θ1r, the arm set point of a fresh controller (a restored state keeps
 *     its own)
 * @param maxTorqueNm the torque the control law clamps to
 * @param filterTimeConstantNs τ of the velocity estimator's low-pass filter
 */
public record ControllerConfig(
        Profile dspProxy,
        long replyTimeoutNs,
        double theta1ReferenceRad,
        double maxTorqueNm,
        long filterTimeConstantNs) {

    /**
     * 10 ms: two thirds of the paper's 15 ms period. A reading takes about 2.6 ms of serial time
     * at 115200 baud, and the client resends a lost frame once after 4 ms.
     */
    public static final long DEFAULT_REPLY_TIMEOUT_NS = 10_000_000L;

    /**
     * Validates every field.
     *
     * @throws NullPointerException     when {@code dspProxy} is null
     * @throws IllegalArgumentException when {@code replyTimeoutNs} is not positive,
     *     {@code theta1ReferenceRad} not finite, {@code maxTorqueNm} not finite and positive, or
     *     {@code filterTimeConstantNs} negative
     */
    public ControllerConfig {
        Objects.requireNonNull(dspProxy, "dspProxy=null: use DspProxy.DEFAULT_PROFILE or the proxy's profile");
        if (replyTimeoutNs <= 0) {
            throw new IllegalArgumentException("replyTimeoutNs=" + replyTimeoutNs
                    + ": must be > 0 and below the Tick period, e.g. 10000000 for 15 ms");
        }
        if (!Double.isFinite(theta1ReferenceRad)) {
            throw new IllegalArgumentException("theta1ReferenceRad=" + theta1ReferenceRad + ": must be finite");
        }
        if (!(maxTorqueNm > 0) || !Double.isFinite(maxTorqueNm)) {
            throw new IllegalArgumentException("maxTorqueNm=" + maxTorqueNm + ": must be finite and > 0");
        }
        if (filterTimeConstantNs < 0) {
            throw new IllegalArgumentException("filterTimeConstantNs=" + filterTimeConstantNs
                    + ": must be >= 0 (0 disables filtering)");
        }
    }

    /**
     * The proxy at {@link DspProxy#DEFAULT_PROFILE}, a 10 ms reply timeout, θ1r = 0, the board's
     * default torque range (0.5 N·m) and the estimator's default filter (5 ms).
     *
     * @return the default settings
     */
    public static ControllerConfig defaults() {
        return new ControllerConfig(DspProxy.DEFAULT_PROFILE, DEFAULT_REPLY_TIMEOUT_NS, 0.0,
                DspBoardConfig.DEFAULT_MAX_TORQUE_NM, VelocityEstimator.DEFAULT_FILTER_TIME_CONSTANT_NS);
    }

    /**
     * A copy talking to another proxy.
     *
     * @param profile the proxy's exact profile or a query that matches it
     * @return the copy
     * @throws NullPointerException when {@code profile} is null
     */
    public ControllerConfig withDspProxy(Profile profile) {
        return new ControllerConfig(profile, replyTimeoutNs, theta1ReferenceRad, maxTorqueNm, filterTimeConstantNs);
    }

    /**
     * A copy with another reply timeout.
     *
     * @param replyTimeout how long a cycle waits for its reading, greater than 0 and below the Tick
     *     period
     * @return the copy
     * @throws IllegalArgumentException when {@code replyTimeout} is not positive
     */
    public ControllerConfig withReplyTimeout(Duration replyTimeout) {
        return new ControllerConfig(dspProxy, Durations.toNs("replyTimeout", replyTimeout), theta1ReferenceRad, maxTorqueNm, filterTimeConstantNs);
    }

    /**
     * A copy with another arm set point.
     *
     * @param radians θ1r, in rad, finite
     * @return the copy
     * @throws IllegalArgumentException when {@code radians} is not finite
     */
    public ControllerConfig withTheta1ReferenceRad(double radians) {
        return new ControllerConfig(dspProxy, replyTimeoutNs, radians, maxTorqueNm, filterTimeConstantNs);
    }
}
