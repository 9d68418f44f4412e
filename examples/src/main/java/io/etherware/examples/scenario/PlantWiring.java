package io.etherware.examples.scenario;

import io.etherware.pendulum.dsp.DspBoardConfig;
import io.etherware.pendulum.serial.DspClient;
import io.etherware.pendulum.serial.SimulatedSerialLink;
import java.time.Duration;

/**
 * How the scenarios wire the simulated plant at a serial line rate: the link at {@code baudRate}, and
 * the board's cycle and the proxy's reply timeout scaled to it, so a faster line is a faster board
 * as on real hardware (a DSP that serves 921,600 baud polls its UART more often than one at 115,200).
 *
 * <p>At the paper's 115,200 baud: 0.5 ms board cycle, 4 ms reply timeout; one control cycle moves 45
 * bytes, 3.9 ms on the wire, so a 1 ms loop needs at least 921,600 baud (0.49 ms on the wire, a
 * 62.5 µs board cycle, 0.5 ms timeout).
 *
 * @param baudRate bits per second on the serial line
 */
public record PlantWiring(int baudRate) {

    /** The paper's RS-232C rate. */
    public static final int DEFAULT_BAUD_RATE = SimulatedSerialLink.Config.DEFAULT_BAUD_RATE;
    /** Slowest accepted: 9,600 baud. */
    public static final int MIN_BAUD_RATE = 9_600;
    /** Fastest accepted: 12 Mbaud (USB full speed). */
    public static final int MAX_BAUD_RATE = 12_000_000;
    /** The shortest board cycle the scaling gives: 50 µs. */
    static final long MIN_BOARD_STEP_NS = 50_000L;
    /** The shortest reply timeout the scaling gives: 0.5 ms. */
    static final long MIN_REPLY_TIMEOUT_NS = 500_000L;

    public PlantWiring {
        requireBaudRate(baudRate);
    }

    /** Throws naming the field unless {@code baudRate} is within the accepted range. */
    public static void requireBaudRate(int baudRate) {
        if (baudRate < MIN_BAUD_RATE || baudRate > MAX_BAUD_RATE) {
            throw new IllegalArgumentException("baudRate=" + baudRate + ": must be within [" + MIN_BAUD_RATE + ", "
                    + MAX_BAUD_RATE + "] (the paper: " + DEFAULT_BAUD_RATE + ")");
        }
    }

    /** The serial link at this rate, no faults. */
    public SimulatedSerialLink.Config link() {
        return SimulatedSerialLink.Config.defaults().withBaudRate(baudRate);
    }

    /** The board with its cycle scaled from 0.5 ms at 115,200 baud (at least 50 µs, at most the default). */
    public DspBoardConfig board() {
        DspBoardConfig defaults = DspBoardConfig.defaults();
        return defaults.withStep(Duration.ofNanos(
                Math.clamp(scaled(defaults.stepNs()), MIN_BOARD_STEP_NS, defaults.stepNs())));
    }

    /** The proxy's client with its reply timeout scaled from 4 ms at 115,200 baud (at least 0.5 ms). */
    public DspClient.Config client() {
        DspClient.Config defaults = DspClient.Config.defaults();
        return defaults.withTimeout(Duration.ofNanos(Math.max(MIN_REPLY_TIMEOUT_NS, scaled(defaults.responseTimeoutNs()))),
                defaults.attempts());
    }

    private long scaled(long nanosAtDefault) {
        return Math.round(nanosAtDefault * (double) DEFAULT_BAUD_RATE / baudRate);
    }
}
