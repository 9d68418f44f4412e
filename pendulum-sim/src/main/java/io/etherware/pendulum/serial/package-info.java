/**
 * The serial protocol between a controller host and the DSP board (frames, CRC-16, streaming
 * decoder), the links that carry it (simulated, jSerialComm), and the synchronous
 * {@link io.etherware.pendulum.serial.DspClient}. Layout in {@code pendulum-sim/SERIAL-PROTOCOL.md}.
 */
package io.etherware.pendulum.serial;
