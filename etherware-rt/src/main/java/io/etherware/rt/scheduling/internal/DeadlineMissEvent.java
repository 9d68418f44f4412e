package io.etherware.rt.scheduling.internal;

import jdk.jfr.Category;
import jdk.jfr.Description;
import jdk.jfr.Event;
import jdk.jfr.Label;
import jdk.jfr.Name;
import jdk.jfr.StackTrace;
import jdk.jfr.Timespan;

/** JFR event: a job completed after its absolute deadline. Committed on its dispatcher thread. */
@Name("io.etherware.rt.DeadlineMiss")
@Label("Deadline Miss")
@Category({"Etherware", "Scheduling"})
@Description("A job of the real-time scheduler completed after its absolute deadline")
@StackTrace(false)
public final class DeadlineMissEvent extends Event {

    @Label("Dispatcher")
    int dispatcher;

    @Label("Component")
    String component;

    @Label("Message")
    String message;

    @Label("Criticality")
    String criticality;

    @Label("Lateness")
    @Description("Completion time minus absolute deadline")
    @Timespan(Timespan.NANOSECONDS)
    long lateness;

    @Label("Start Latency")
    @Timespan(Timespan.NANOSECONDS)
    long startLatency;

    @Label("Execution Time")
    @Timespan(Timespan.NANOSECONDS)
    long executionTime;
}
