package io.etherware.pendulum.components;

import io.etherware.core.message.Contents;

/**
 * A request to the {@link DspProxy} for its counters, answered by a {@link DspProxyStatus}.
 * Registered as {@value PendulumContents#STATUS_REQUEST}. Immutable.
 *
 * @param includeBoard also read the board's STATUS frame over the link (a serial exchange of
 *     about 4 ms at 115200 baud, taken from the control loop's time on that link)
 */
public record StatusRequest(boolean includeBoard) implements Contents {}
