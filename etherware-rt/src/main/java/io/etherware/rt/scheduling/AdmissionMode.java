package io.etherware.rt.scheduling;

/** What admission control does when a declared stream would make a dispatcher unschedulable. */
public enum AdmissionMode {
    /** Accept the stream and log a warning naming the dispatcher, its utilization and bound. */
    WARN,
    /** Refuse the stream with an {@link AdmissionRejectedException}; the stream is not added. */
    REJECT
}
