package io.etherware.pendulum.components;

import io.etherware.core.message.Contents;
import io.etherware.pendulum.serial.BoardStatus;
import io.etherware.pendulum.serial.DspClient;
import java.util.Objects;

/**
 * The {@link DspProxy}'s reply to a {@link StatusRequest}. Registered as
 * {@value PendulumContents#DSP_STATUS}. Immutable.
 *
 * @param proxy the proxy's own counters
 * @param link the serial client's counters (frames sent, timeouts, rejected frames)
 * @param board the board's flags and counters, or null if not asked for or not read
 * @param boardError why the board's status could not be read, or null
 */
public record DspProxyStatus(
        DspProxyCounters proxy,
        DspClient.Counters link,
        BoardStatus board,
        String boardError) implements Contents {

    /** Rejects a missing proxy or link part. */
    public DspProxyStatus {
        Objects.requireNonNull(proxy, "proxy");
        Objects.requireNonNull(link, "link");
    }
}
