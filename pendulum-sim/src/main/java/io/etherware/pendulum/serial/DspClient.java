package io.etherware.pendulum.serial;

import io.etherware.core.time.NodeClock;
import java.io.IOException;
import java.util.Objects;

/**
 * A synchronous client of the DSP board over a {@link SerialLink}: each call sends one request
 * and waits for its reply (matched by sequence number) up to the response timeout. This is what
 * the DSPProxy component uses, and what a plain control loop can use directly.
 *
 * <p>Replies to earlier, timed-out requests are recognized by their sequence number and dropped
 * (counted as stale); corrupt bytes are rejected by the {@link FrameDecoder} and counted. A
 * timeout throws {@link DspTimeoutException} naming the request, the wait and the link's error
 * counts; the client stays usable.
 *
 * <p>Not thread-safe: one caller at a time (the proxy's dispatcher thread). The clock must be the
 * link's time base: the system clock for real links, the {@code LockStepClock} in lock step.
 */
public final class DspClient {

    /**
     * Client settings. Immutable; validated at construction.
     *
     * @param countsPerRevolution the encoders' resolution, to turn counts into radians
     * @param responseTimeoutNs how long to wait for each reply
     */
    public record Config(int countsPerRevolution, long responseTimeoutNs) {

        /** 4096 counts per revolution. */
        public static final int DEFAULT_COUNTS_PER_REVOLUTION = 4096;
        /** 10 ms: a 19-byte reply at 115200 baud takes 1.6 ms, the board answers within 0.5 ms. */
        public static final long DEFAULT_RESPONSE_TIMEOUT_NS = 10_000_000L;

        /** Validates the fields. */
        public Config {
            if (countsPerRevolution <= 0) {
                throw new IllegalArgumentException("countsPerRevolution=" + countsPerRevolution
                        + ": must be > 0");
            }
            if (responseTimeoutNs <= 0) {
                throw new IllegalArgumentException("responseTimeoutNs=" + responseTimeoutNs
                        + ": must be > 0");
            }
        }

        /** 4096 counts per revolution, 10 ms timeout. */
        public static Config defaults() {
            return new Config(DEFAULT_COUNTS_PER_REVOLUTION, DEFAULT_RESPONSE_TIMEOUT_NS);
        }

        /** A copy with another response timeout. */
        public Config withResponseTimeoutNs(long timeoutNs) {
            return new Config(countsPerRevolution, timeoutNs);
        }
    }

    /**
     * The client's counters. Immutable snapshot.
     *
     * @param requests requests sent
     * @param timeouts requests that got no reply in time
     * @param staleReplies valid replies that answered no pending request (late or unexpected)
     * @param framesRejected corrupt candidate frames received
     * @param bytesDiscarded received bytes skipped while resynchronizing
     */
    public record Counters(long requests, long timeouts, long staleReplies, long framesRejected,
            long bytesDiscarded) {}

    private final SerialLink link;
    private final NodeClock clock;
    private final Config config;
    private final double radiansPerCount;
    private final FrameDecoder decoder = new FrameDecoder();
    private final byte[] txFrame = new byte[DspProtocol.MAX_FRAME_BYTES];
    private final byte[] rxBuffer = new byte[256];
    private final byte[] replyPayload = new byte[DspProtocol.MAX_PAYLOAD_BYTES];
    private final FrameDecoder.Listener onFrame = this::onFrame;
    private int nextSequence;
    private int awaitedType = -1;
    private int awaitedSequence = -1;
    private boolean replied;
    private long lastRawTimeUs = -1;
    private long unwrappedTimeUs;
    private long requests;
    private long timeouts;
    private long staleReplies;

    /** A client on {@code link}, timing its waits with {@code clock}. */
    public DspClient(SerialLink link, NodeClock clock, Config config) {
        this.link = Objects.requireNonNull(link, "link");
        this.clock = Objects.requireNonNull(clock, "clock");
        this.config = Objects.requireNonNull(config, "config");
        this.radiansPerCount = 2.0 * Math.PI / config.countsPerRevolution();
    }

    /** Samples both encoders. */
    public Angles readAngles() throws DspException {
        int sequence = send(DspProtocol.encodeRequest(txFrame, DspProtocol.READ_ANGLES, allocateSequence()),
                DspProtocol.READ_ANGLES);
        await(DspProtocol.ANGLES, sequence, "READ_ANGLES");
        int counts1 = DspProtocol.getI32(replyPayload, 2);
        int counts2 = DspProtocol.getI32(replyPayload, 6);
        long timeUs = unwrap(DspProtocol.getU32(replyPayload, 10));
        return new Angles(sequence, counts1, counts2, timeUs, counts1 * radiansPerCount,
                counts2 * radiansPerCount);
    }

    /** Commands the motor torque; the board clamps it to its range and says so in the ACK. */
    public TorqueAck setTorque(double torqueNm) throws DspException {
        int sequence = allocateSequence();
        send(DspProtocol.encodeSetTorque(txFrame, sequence, torqueNm), DspProtocol.SET_TORQUE);
        await(DspProtocol.ACK, sequence, "SET_TORQUE");
        return new TorqueAck(sequence, replyPayload[2] & 0xFF);
    }

    /** Reads the board's fault flags and counters. */
    public BoardStatus readStatus() throws DspException {
        int sequence = send(DspProtocol.encodeRequest(txFrame, DspProtocol.READ_STATUS, allocateSequence()),
                DspProtocol.READ_STATUS);
        await(DspProtocol.STATUS, sequence, "READ_STATUS");
        return BoardStatus.decode(replyPayload, 0);
    }

    /** The counters so far. */
    public Counters counters() {
        return new Counters(requests, timeouts, staleReplies, decoder.framesRejected(),
                decoder.bytesDiscarded());
    }

    /** The link this client talks over. */
    public SerialLink link() {
        return link;
    }

    private int allocateSequence() {
        int sequence = nextSequence;
        nextSequence = (nextSequence + 1) & 0xFFFF;
        return sequence;
    }

    /** Writes the frame in {@link #txFrame}; returns the sequence it carries. */
    private int send(int frameLength, int type) throws DspException {
        int sequence = DspProtocol.getU16(txFrame, DspProtocol.HEADER_BYTES);
        requests++;
        try {
            link.write(txFrame, 0, frameLength);
        } catch (IOException e) {
            throw new DspException("cannot send " + DspProtocol.typeName(type) + " #" + sequence
                    + " on " + link.name() + ": " + e.getMessage(), e);
        }
        return sequence;
    }

    private void await(int type, int sequence, String request) throws DspException {
        awaitedType = type;
        awaitedSequence = sequence;
        replied = false;
        long startNs = clock.nanoTime();
        long deadlineNs = startNs + config.responseTimeoutNs();
        try {
            while (!replied) {
                long remainingNs = deadlineNs - clock.nanoTime();
                if (remainingNs <= 0) {
                    timeouts++;
                    throw new DspTimeoutException("no " + DspProtocol.typeName(type) + " reply to "
                            + request + " #" + sequence + " on " + link.name() + " within "
                            + config.responseTimeoutNs() / 1_000 + " µs (frames rejected so far: "
                            + decoder.framesRejected() + ", bytes discarded: "
                            + decoder.bytesDiscarded() + ", timeouts: " + timeouts + ")");
                }
                int n;
                try {
                    n = link.read(rxBuffer, 0, rxBuffer.length, remainingNs);
                } catch (IOException e) {
                    throw new DspException("cannot read the reply to " + request + " #" + sequence
                            + " on " + link.name() + ": " + e.getMessage(), e);
                }
                if (n > 0) {
                    decoder.accept(rxBuffer, 0, n, onFrame);
                }
            }
        } finally {
            awaitedType = -1;
            awaitedSequence = -1;
        }
    }

    private void onFrame(int type, byte[] payload, int offset, int length) {
        int sequence = length >= 2 ? DspProtocol.getU16(payload, offset) : -1;
        if (!replied && type == awaitedType && sequence == awaitedSequence) {
            System.arraycopy(payload, offset, replyPayload, 0, length);
            replied = true;
        } else {
            staleReplies++;
        }
    }

    /** Extends the board's 32-bit µs clock, tolerating a small step backwards (signed delta). */
    private long unwrap(long rawTimeUs) {
        if (lastRawTimeUs < 0) {
            unwrappedTimeUs = rawTimeUs;
        } else {
            unwrappedTimeUs += (int) (rawTimeUs - lastRawTimeUs);
        }
        lastRawTimeUs = rawTimeUs;
        return unwrappedTimeUs;
    }
}
