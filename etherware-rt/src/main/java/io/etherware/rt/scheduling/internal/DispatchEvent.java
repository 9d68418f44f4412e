package io.etherware.rt.scheduling.internal;

import jdk.jfr.Category;
import jdk.jfr.Description;
import jdk.jfr.Event;
import jdk.jfr.Label;
import jdk.jfr.Name;
import jdk.jfr.StackTrace;
import jdk.jfr.Timespan;

/**
 * JFR event: one job taken by a dispatcher, from the start of its run to its end (the event's
 * duration). In JDK Mission Control, the per-thread view of these events is the schedule.
 * Written and committed only on its dispatcher thread.
 */
@Name("io.etherware.rt.Dispatch")
@Label("Dispatch")
@Category({"Etherware", "Scheduling"})
@Description("A job run (or parked, when its component was busy) by a dispatcher of the real-time scheduler")
@StackTrace(false)
public final class DispatchEvent extends Event {

    @Label("Dispatcher")
    int dispatcher;

    @Label("Component")
    String component;

    @Label("Message")
    String message;

    @Label("Criticality")
    String criticality;

    @Label("Queue Key")
    @Description("The placement key: smaller runs first within the dispatcher")
    long key;

    @Label("Start Latency")
    @Description("From the job's release to the start of its run")
    @Timespan(Timespan.NANOSECONDS)
    long startLatency;

    @Label("Ran")
    @Description("False when the job was parked because its component was busy on another dispatcher")
    boolean ran;
}
