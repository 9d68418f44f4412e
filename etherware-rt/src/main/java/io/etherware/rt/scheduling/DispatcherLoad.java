package io.etherware.rt.scheduling;

/**
 * One dispatcher's declared periodic load, as admission control sees it. Immutable.
 *
 * @param dispatcherId the dispatcher
 * @param policy       how its queue orders jobs
 * @param streams      how many declared streams it runs
 * @param utilization  the sum of their {@code wcet / period}
 * @param bound        the policy's utilization bound for that many streams
 */
public record DispatcherLoad(int dispatcherId, QueuePolicy policy, int streams, double utilization, double bound) {

    /**
     * Whether the utilization stays within the bound.
     *
     * @return true when {@code utilization <= bound}, allowing for floating-point rounding
     */
    public boolean isSchedulable() {
        return utilization <= bound + 1e-12;
    }

    /** {@code dispatcher 1 (EARLIEST_DEADLINE_FIRST): U=0.730 <= bound 1.000 with 2 streams}. */
    @Override
    public String toString() {
        return String.format(java.util.Locale.ROOT, "dispatcher %d (%s): U=%.3f %s bound %.3f with %d stream%s",
                dispatcherId, policy, utilization, isSchedulable() ? "<=" : ">", bound, streams, streams == 1 ? "" : "s");
    }
}
