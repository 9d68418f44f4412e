package io.etherware.pendulum.components;

import io.etherware.core.message.Contents;

/**
 * A request to the {@link DspProxy} for one encoder sample, answered by an {@link AnglesReading}
 * or a {@link DspFault}. Registered as {@value PendulumContents#READ_ANGLES}. Immutable.
 *
 * @param cycle the requesting control cycle (the Tick's sequence), echoed in the reply for traces
 */
public record ReadAngles(long cycle) implements Contents {}
