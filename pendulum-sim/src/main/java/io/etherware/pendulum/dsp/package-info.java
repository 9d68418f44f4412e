/**
 * The simulated DSP board: it owns the pendulum, samples quantized encoders, holds the motor
 * torque, guards it with a watchdog, and serves the serial protocol, in real time or lock step.
 */
package io.etherware.pendulum.dsp;
