/**
 * The rotary inverted pendulum of the paper's Section VI-A: the plant, controller design and the
 * per-cycle control law, the simulated DSP board, the serial protocol with its links, and the
 * Etherware components that close the loop (DspProxy and PendulumController).
 *
 * <p>The pseudo-terminal code in {@code io.etherware.pendulum.serial.internal} calls libc through
 * the FFM API: run with {@code --enable-native-access=io.etherware.pendulum} (or ALL-UNNAMED on
 * the class path) to use it without a warning.
 */
module io.etherware.pendulum {
    requires transitive io.etherware.core;
    requires com.fazecast.jSerialComm;

    exports io.etherware.pendulum.components;
    exports io.etherware.pendulum.control;
    exports io.etherware.pendulum.dsp;
    exports io.etherware.pendulum.linalg;
    exports io.etherware.pendulum.plant;
    exports io.etherware.pendulum.serial;
    exports io.etherware.pendulum.sim;
}
