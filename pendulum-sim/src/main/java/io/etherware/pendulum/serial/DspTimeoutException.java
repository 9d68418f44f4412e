package io.etherware.pendulum.serial;

/** The DSP board did not answer a request within the client's response timeout. */
public class DspTimeoutException extends DspException {

    private static final long serialVersionUID = 1L;

    /**
     * A timeout with its explanation.
     *
     * @param message the request that went unanswered and how long the client waited
     */
    public DspTimeoutException(String message) {
        super(message);
    }
}
