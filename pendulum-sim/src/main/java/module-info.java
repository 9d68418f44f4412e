/** The rotary inverted pendulum, its simulated DSP board, serial links and control components. */
module io.etherware.pendulum {
    requires transitive io.etherware.core;
    requires com.fazecast.jSerialComm;
}
