package io.etherware.rt.scheduling;

/**
 * Thrown by {@link AdmissionControl#declare} in {@link AdmissionMode#REJECT} mode when a stream
 * would make its dispatcher unschedulable. The message names the dispatcher, its utilization with
 * the stream and the bound. Thrown on the declaring thread.
 */
public final class AdmissionRejectedException extends RuntimeException {

    private final transient PeriodicStream stream;
    private final transient DispatcherLoad loadWithStream;

    /**
     * An exception whose message names the stream, its QoS and the load it would have caused.
     *
     * @param stream         the rejected stream
     * @param loadWithStream its dispatcher's load as it would have been with the stream
     */
    public AdmissionRejectedException(PeriodicStream stream, DispatcherLoad loadWithStream) {
        super("stream to " + stream.target() + " (" + stream.qos().criticality() + ", period "
                + stream.qos().periodNs() + " ns, wcet " + stream.qos().wcetNs() + " ns) rejected: "
                + loadWithStream);
        this.stream = stream;
        this.loadWithStream = loadWithStream;
    }

    /**
     * The rejected stream.
     *
     * @return the stream; null in a deserialized copy of this exception
     */
    public PeriodicStream stream() {
        return stream;
    }

    /**
     * The dispatcher's load as it would have been with the stream.
     *
     * @return the load, over its policy's bound; null in a deserialized copy of this exception
     */
    public DispatcherLoad loadWithStream() {
        return loadWithStream;
    }
}
