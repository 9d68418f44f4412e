package io.etherware.pendulum.components;

/**
 * One control cycle as the {@link PendulumController} saw it, for plots and checks: what it
 * measured, what it commanded and when. Times are on the controller node's monotonic clock.
 * Immutable.
 *
 * @param cycle the Tick's sequence
 * @param releaseNs the Tick's scheduled release
 * @param startNs when the controller handled the Tick
 * @param readoutNs when the reading (or its failure) reached the controller; the torque command
 *     left right after
 * @param outcome whether a torque was commanded
 * @param theta1Rad measured θ1 (NaN when missed)
 * @param theta2Rad measured θ2 (NaN when missed)
 * @param theta1RateRadPerS estimated θ̇1 (NaN when missed)
 * @param theta2RateRadPerS estimated θ̇2 (NaN when missed)
 * @param dspTimeUs the board's time of the sample (-1 when missed)
 * @param torqueNm the torque commanded (NaN when missed: the board holds the previous one)
 * @param gainVersion the version of the gain set that computed it
 */
public record ControlCycle(
        long cycle,
        long releaseNs,
        long startNs,
        long readoutNs,
        Outcome outcome,
        double theta1Rad,
        double theta2Rad,
        double theta1RateRadPerS,
        double theta2RateRadPerS,
        long dspTimeUs,
        double torqueNm,
        int gainVersion) {

    /** What became of a cycle. */
    public enum Outcome {
        /** A reading came and a torque was sent. */
        COMMANDED,
        /** The reading failed (timeout, undeliverable, DSP fault); no torque was sent. */
        MISSED
    }

    /** A cycle whose reading failed. */
    static ControlCycle missed(long cycle, long releaseNs, long startNs, long readoutNs, int gainVersion) {
        return new ControlCycle(cycle, releaseNs, startNs, readoutNs, Outcome.MISSED, Double.NaN, Double.NaN,
                Double.NaN, Double.NaN, -1L, Double.NaN, gainVersion);
    }

    /**
     * How late the controller started after the release: dispatch latency plus queueing.
     *
     * @return {@code startNs - releaseNs}, in nanoseconds
     */
    public long startLatenessNs() {
        return startNs - releaseNs;
    }

    /**
     * From the release to the torque command: the cycle's response time on the controller's side.
     *
     * @return {@code readoutNs - releaseNs}, in nanoseconds
     */
    public long responseNs() {
        return readoutNs - releaseNs;
    }
}
