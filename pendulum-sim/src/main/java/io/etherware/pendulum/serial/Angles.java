package io.etherware.pendulum.serial;

/**
 * One encoder sample from the DSP board, as an ANGLES reply carries it, with the angles in
 * radians. Immutable value; thread-safe.
 *
 * @param sequence the request's sequence number, echoed
 * @param encoder1Counts joint-1 (arm) encoder count, multi-turn
 * @param encoder2Counts joint-2 (pendulum) encoder count, multi-turn, 0 upright
 * @param dspTimeUs the board's time of the sample in µs, unwrapped from the wire's 32 bits
 * @param theta1Rad θ1 = counts × 2π / counts-per-revolution
 * @param theta2Rad θ2 = counts × 2π / counts-per-revolution
 */
public record Angles(
        int sequence,
        int encoder1Counts,
        int encoder2Counts,
        long dspTimeUs,
        double theta1Rad,
        double theta2Rad) {}
