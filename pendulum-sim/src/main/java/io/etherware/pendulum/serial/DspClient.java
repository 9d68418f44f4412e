package io.etherware.pendulum.serial;

import io.etherware.core.time.Durations;
import io.etherware.core.time.NodeClock;
import java.io.IOException;
import java.time.Duration;
import java.util.Objects;

/**
 * A synchronous client of the DSP board over a {@link SerialLink}: each call sends a request
 * and waits for its reply (matched by sequence number) up to the response timeout, resending it
 * up to {@link Config#attempts()} times in all. Every request is idempotent — a torque command
 * sets an absolute value — so a resend after a lost reply is harmless. This is what the DSPProxy
 * component uses, and what a plain control loop can use directly.
 *
 * <p>Replies to earlier, timed-out attempts are recognized by their sequence number and dropped
 * (counted as stale); corrupt bytes are rejected by the {@link FrameDecoder} and counted. When
 * every attempt times out the call throws {@link DspTimeoutException} naming the request, the
 * wait and the link's error counts; the client stays usable.
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
     * @param attempts how many times a request is sent before the call fails, at least 1
     */
    public record Config(int countsPerRevolution, long responseTimeoutNs, int attempts) {

        /** 4096 counts per revolution. */
        public static final int DEFAULT_COUNTS_PER_REVOLUTION = 4096;
        /**
         * 4 ms: at 115200 baud a READ_ANGLES (7 bytes) and its reply (19 bytes) take 2.3 ms on the
         * wire and the board answers within its 0.5 ms cycle. Two attempts of a read and of a
         * command then fit in the paper's 15 ms period.
         */
        public static final long DEFAULT_RESPONSE_TIMEOUT_NS = 4_000_000L;
        /** One resend after a lost frame. */
        public static final int DEFAULT_ATTEMPTS = 2;

        /**
         * Validates the fields.
         *
         * @throws IllegalArgumentException when {@code countsPerRevolution} or
         *                                  {@code responseTimeoutNs} is not positive, or
         *                                  {@code attempts} is outside [1, 10]
         */
        public Config {
            if (countsPerRevolution <= 0) {
                throw new IllegalArgumentException("countsPerRevolution=" + countsPerRevolution
                        + ": must be > 0");
            }
            if (responseTimeoutNs <= 0) {
                throw new IllegalArgumentException("responseTimeoutNs=" + responseTimeoutNs
                        + ": must be > 0");
            }
            if (attempts < 1 || attempts > 10) {
                throw new IllegalArgumentException("attempts=" + attempts + ": must be within [1, 10]");
            }
        }

        /**
         * 4096 counts per revolution, 4 ms timeout, 2 attempts.
         *
         * @return the default settings
         */
        public static Config defaults() {
            return new Config(DEFAULT_COUNTS_PER_REVOLUTION, DEFAULT_RESPONSE_TIMEOUT_NS,
                    DEFAULT_ATTEMPTS);
        }

        /**
         * A copy with another encoder resolution.
         *
         * @param counts encoder counts per revolution, greater than 0
         * @return the copy
         * @throws IllegalArgumentException when {@code counts} is not positive
         */
        public Config withCountsPerRevolution(int counts) {
            return new Config(counts, responseTimeoutNs, attempts);
        }

        /**
         * A copy with another response timeout and number of attempts.
         *
         * @param timeout      how long to wait for each reply, greater than 0
         * @param attemptCount how many times a request is sent before the call fails, in [1, 10]
         * @return the copy
         * @throws IllegalArgumentException when a value is out of range
         */
        public Config withTimeout(Duration timeout, int attemptCount) {
            return new Config(countsPerRevolution, Durations.toNs("timeout", timeout), attemptCount);
        }
    }

    /**
     * The client's counters. Immutable snapshot.
     *
     * @param requests request frames sent, resends included
     * @param timeouts attempts that got no reply in time (resent or failed)
     * @param failures calls that failed after all their attempts
     * @param staleReplies valid replies that answered no pending request (late or unexpected)
     * @param framesRejected corrupt candidate frames received
     * @param bytesDiscarded received bytes skipped while resynchronizing
     */
    public record Counters(long requests, long timeouts, long failures, long staleReplies,
            long framesRejected, long bytesDiscarded) {}

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
    private long failures;
    private long staleReplies;

    /**
     * A client on a link. The client does not close the link.
     *
     * @param link   the link to the board; this client must be its only reader and writer
     * @param clock  times the waits for replies; the link's time base
     * @param config the client's settings
     * @throws NullPointerException when an argument is null
     */
    public DspClient(SerialLink link, NodeClock clock, Config config) {
        this.link = Objects.requireNonNull(link, "link");
        this.clock = Objects.requireNonNull(clock, "clock");
        this.config = Objects.requireNonNull(config, "config");
        this.radiansPerCount = 2.0 * Math.PI / config.countsPerRevolution();
    }

    /**
     * Samples both encoders. Blocks the calling thread for the exchange: up to
     * {@link Config#attempts()} × {@link Config#responseTimeoutNs()}.
     *
     * @return the sample, with the board's time stamp unwrapped to 64 bits and the angles in rad
     * @throws DspTimeoutException when no attempt got its reply in time
     * @throws DspException        when the link fails
     */
    public Angles readAngles() throws DspException {
        exchange(DspProtocol.READ_ANGLES, DspProtocol.ANGLES, 0.0);
        int counts1 = DspProtocol.getI32(replyPayload, 2);
        int counts2 = DspProtocol.getI32(replyPayload, 6);
        long timeUs = unwrap(DspProtocol.getU32(replyPayload, 10));
        return new Angles(DspProtocol.getU16(replyPayload, 0), counts1, counts2, timeUs,
                counts1 * radiansPerCount, counts2 * radiansPerCount);
    }

    /**
     * Commands the motor torque; the board clamps it to its range and says so in the ACK. Blocks
     * the calling thread for the exchange: up to {@link Config#attempts()} ×
     * {@link Config#responseTimeoutNs()}.
     *
     * @param torqueNm the torque to apply, in N·m; NaN is sent as 0
     * @return the board's acknowledgement
     * @throws DspTimeoutException when no attempt got its reply in time
     * @throws DspException        when the link fails
     */
    public TorqueAck setTorque(double torqueNm) throws DspException {
        exchange(DspProtocol.SET_TORQUE, DspProtocol.ACK, torqueNm);
        return new TorqueAck(DspProtocol.getU16(replyPayload, 0), replyPayload[2] & 0xFF);
    }

    /**
     * Reads the board's fault flags and counters. Its 40-byte reply is twice an ANGLES reply, so
     * each attempt waits twice the response timeout.
     *
     * @return the board's flags and counters
     * @throws DspTimeoutException when no attempt got its reply in time
     * @throws DspException        when the link fails
     */
    public BoardStatus readStatus() throws DspException {
        exchange(DspProtocol.READ_STATUS, DspProtocol.STATUS, 0.0);
        return BoardStatus.decode(replyPayload, 0);
    }

    /**
     * The counters so far.
     *
     * @return a new snapshot, including the decoder's rejected frames and discarded bytes
     */
    public Counters counters() {
        return new Counters(requests, timeouts, failures, staleReplies, decoder.framesRejected(),
                decoder.bytesDiscarded());
    }

    /**
     * The link this client talks over.
     *
     * @return the link given at construction
     */
    public SerialLink link() {
        return link;
    }

    private int allocateSequence() {
        int sequence = nextSequence;
        nextSequence = (nextSequence + 1) & 0xFFFF;
        return sequence;
    }

    /** Sends the request, resending on timeout; leaves the reply's payload in {@link #replyPayload}. */
    private void exchange(int requestType, int replyType, double torqueNm) throws DspException {
        for (int attempt = 1; ; attempt++) {
            int sequence = allocateSequence();
            int frameLength = requestType == DspProtocol.SET_TORQUE
                    ? DspProtocol.encodeSetTorque(txFrame, sequence, torqueNm)
                    : DspProtocol.encodeRequest(txFrame, requestType, sequence);
            requests++;
            try {
                link.write(txFrame, 0, frameLength);
            } catch (IOException e) {
                failures++;
                throw new DspException("cannot send " + DspProtocol.typeName(requestType) + " #"
                        + sequence + " on " + link.name() + ": " + e.getMessage(), e);
            }
            if (await(replyType, sequence, requestType)) {
                return;
            }
            timeouts++;
            if (attempt == config.attempts()) {
                failures++;
                throw new DspTimeoutException("no " + DspProtocol.typeName(replyType) + " reply to "
                        + DspProtocol.typeName(requestType) + " on " + link.name() + " after "
                        + attempt + " attempt(s) of " + timeoutFor(replyType) / 1_000
                        + " µs (last #" + sequence + "; frames rejected so far: "
                        + decoder.framesRejected() + ", bytes discarded: "
                        + decoder.bytesDiscarded() + ", failed calls: " + failures + ")");
            }
        }
    }

    /** Waits for the reply to one attempt; false on timeout. */
    private boolean await(int type, int sequence, int requestType) throws DspException {
        awaitedType = type;
        awaitedSequence = sequence;
        replied = false;
        long deadlineNs = clock.nanoTime() + timeoutFor(type);
        try {
            while (!replied) {
                long remainingNs = deadlineNs - clock.nanoTime();
                if (remainingNs <= 0) {
                    return false;
                }
                int n;
                try {
                    n = link.read(rxBuffer, 0, rxBuffer.length, remainingNs);
                } catch (IOException e) {
                    failures++;
                    throw new DspException("cannot read the reply to "
                            + DspProtocol.typeName(requestType) + " #" + sequence + " on "
                            + link.name() + ": " + e.getMessage(), e);
                }
                if (n > 0) {
                    decoder.accept(rxBuffer, 0, n, onFrame);
                }
            }
            return true;
        } finally {
            awaitedType = -1;
            awaitedSequence = -1;
        }
    }

    private long timeoutFor(int replyType) {
        return replyType == DspProtocol.STATUS ? 2 * config.responseTimeoutNs()
                : config.responseTimeoutNs();
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
