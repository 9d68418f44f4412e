package io.etherware.pendulum.components;

import io.etherware.core.message.Contents;
import java.util.Objects;

/**
 * The {@link DspProxy}'s reply when it could not serve a request: the serial exchange failed, or
 * the request was not one it serves. A serial
 * failure is an expected event of the plant, not a bug of the proxy: it is answered and counted
 * instead of thrown, so it never triggers a restart. Registered as
 * {@value PendulumContents#DSP_FAULT}. Immutable.
 *
 * @param cycle the requesting cycle, echoed (0 for requests that carry none)
 * @param kind what failed
 * @param detail the client's error message: request, wait and link error counts
 */
public record DspFault(long cycle, Kind kind, String detail) implements Contents {

    /** What failed. */
    public enum Kind {
        /** The board did not answer within the client's attempts. */
        TIMEOUT,
        /** The link itself failed (closed, port error). */
        LINK_ERROR,
        /** The request's contents are not something the proxy serves. */
        UNSUPPORTED
    }

    /** Rejects nulls. */
    public DspFault {
        Objects.requireNonNull(kind, "kind");
        Objects.requireNonNull(detail, "detail");
    }
}
