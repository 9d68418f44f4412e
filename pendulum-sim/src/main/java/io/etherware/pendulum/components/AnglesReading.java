package io.etherware.pendulum.components;

import io.etherware.core.message.Contents;

/**
 * The {@link DspProxy}'s reply to {@link ReadAngles}: one encoder sample of the DSP board, as its
 * ANGLES frame carried it, with the angles already in radians. Registered as
 * {@value PendulumContents#ANGLES}. Immutable.
 *
 * @param cycle the requesting cycle, echoed
 * @param serialSequence the sequence number of the serial exchange that sampled it
 * @param encoder1Counts joint-1 (arm) encoder count, multi-turn
 * @param encoder2Counts joint-2 (pendulum) encoder count, multi-turn, 0 upright
 * @param dspTimeUs the board's time of the sample, µs, unwrapped (monotonic)
 * @param theta1Rad θ1 from encoder 1
 * @param theta2Rad θ2 from encoder 2, 0 upright
 */
public record AnglesReading(
        long cycle,
        int serialSequence,
        int encoder1Counts,
        int encoder2Counts,
        long dspTimeUs,
        double theta1Rad,
        double theta2Rad) implements Contents {

    /** Rejects non-finite angles: a peer's bad reading must never reach the control law. */
    public AnglesReading {
        if (!Double.isFinite(theta1Rad) || !Double.isFinite(theta2Rad)) {
            throw new IllegalArgumentException("theta1Rad=" + theta1Rad + ", theta2Rad=" + theta2Rad
                    + ": angles must be finite");
        }
    }
}
