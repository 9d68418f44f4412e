package io.etherware.pendulum.serial;

import java.io.IOException;

/** A request to the DSP board failed: the link failed, or the reply did not come. */
public class DspException extends IOException {

    private static final long serialVersionUID = 1L;

    /**
     * An error with its explanation.
     *
     * @param message what failed, naming the request
     */
    public DspException(String message) {
        super(message);
    }

    /**
     * An error caused by a link failure.
     *
     * @param message what failed, naming the request
     * @param cause   the link's exception
     */
    public DspException(String message, Throwable cause) {
        super(message, cause);
    }
}
