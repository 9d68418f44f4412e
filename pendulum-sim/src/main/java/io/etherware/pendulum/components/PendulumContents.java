package io.etherware.pendulum.components;

import io.etherware.core.message.ContentsTypes;

/**
 * The wire names of the pendulum components' messages and states. The names are part of the wire
 * format: never rename one, register a new type instead.
 *
 * <p>{@link #register()} is idempotent and thread-safe; {@link DspProxy} and
 * {@link PendulumController} call it when they load, and a node that only decodes these messages
 * (a remote monitor) calls it itself.
 */
public final class PendulumContents {

    /** {@link ReadAngles}. */
    public static final String READ_ANGLES = "pendulum.read-angles";
    /** {@link AnglesReading}. */
    public static final String ANGLES = "pendulum.angles";
    /** {@link SetTorque}. */
    public static final String SET_TORQUE = "pendulum.set-torque";
    /** {@link DspFault}. */
    public static final String DSP_FAULT = "pendulum.dsp-fault";
    /** {@link StatusRequest}. */
    public static final String STATUS_REQUEST = "pendulum.status-request";
    /** {@link DspProxyStatus}. */
    public static final String DSP_STATUS = "pendulum.dsp-status";
    /** {@link DspProxyCounters}, the proxy's component state. */
    public static final String DSP_PROXY_COUNTERS = "pendulum.dsp-proxy-counters";
    /** {@link ControllerState}, the controller's component state. */
    public static final String CONTROLLER_STATE = "pendulum.controller-state";

    private PendulumContents() {}

    /** Registers every type in {@link ContentsTypes#shared()}. Idempotent. */
    public static void register() {
        register(ContentsTypes.shared());
    }

    /**
     * Registers every type in {@code types}. Idempotent.
     *
     * @param types the registry, e.g. the one a codec in a test uses
     * @return {@code types}, for chaining
     * @throws IllegalArgumentException if one of the names is taken by another type
     */
    public static ContentsTypes register(ContentsTypes types) {
        return types
                .register(READ_ANGLES, ReadAngles.class)
                .register(ANGLES, AnglesReading.class)
                .register(SET_TORQUE, SetTorque.class)
                .register(DSP_FAULT, DspFault.class)
                .register(STATUS_REQUEST, StatusRequest.class)
                .register(DSP_STATUS, DspProxyStatus.class)
                .register(DSP_PROXY_COUNTERS, DspProxyCounters.class)
                .register(CONTROLLER_STATE, ControllerState.class);
    }
}
