package io.etherware.pendulum.serial;

import io.etherware.pendulum.sim.LockStepClock;
import java.io.IOException;
import java.io.InterruptedIOException;
import java.util.SplittableRandom;
import java.util.concurrent.locks.Condition;
import java.util.concurrent.locks.ReentrantLock;

/**
 * An in-process serial cable: two {@link SerialLink} ends, host and board, whose bytes arrive
 * with the transmission delay of a real UART — {@code bitsPerByte / baudRate} per byte, one byte
 * after the other (115200 baud 8N1: 86.8 µs a byte) — with optional seeded fault injection: a
 * byte may be dropped, or have one random bit flipped.
 *
 * <p>Two time bases: {@link #realTime} (the monotonic clock; a reader sleeps until the bytes
 * arrive) and {@link #lockStep} (a {@link LockStepClock}; a reader's wait advances simulated
 * time, so the run is deterministic). Each end follows the {@link SerialLink} threading contract.
 */
public final class SimulatedSerialLink {

    /**
     * The cable's settings. Immutable; validated at construction.
     *
     * @param baudRate bits per second on the wire
     * @param bitsPerByte bits per character including start and stop bits (8N1: 10)
     * @param bitFlipProbabilityPerByte chance that a byte arrives with one bit flipped
     * @param dropProbabilityPerByte chance that a byte is lost
     * @param seed the fault injection's random seed
     * @param receiveBufferBytes bytes a receiver holds before further bytes overrun and are lost
     */
    public record Config(int baudRate, int bitsPerByte, double bitFlipProbabilityPerByte,
            double dropProbabilityPerByte, long seed, int receiveBufferBytes) {

        /** 115200 baud, the paper's RS-232C rate. */
        public static final int DEFAULT_BAUD_RATE = 115_200;

        /**
         * Validates every field; messages name the field and value.
         *
         * @throws IllegalArgumentException when {@code baudRate} is outside [50, 20000000],
         *                                  {@code bitsPerByte} outside [8, 13], a probability
         *                                  outside [0, 1], or {@code receiveBufferBytes} smaller
         *                                  than one frame ({@value DspProtocol#MAX_FRAME_BYTES})
         */
        public Config {
            if (baudRate < 50 || baudRate > 20_000_000) {
                throw new IllegalArgumentException("baudRate=" + baudRate + ": must be within [50, 20000000]");
            }
            if (bitsPerByte < 8 || bitsPerByte > 13) {
                throw new IllegalArgumentException("bitsPerByte=" + bitsPerByte
                        + ": must be within [8, 13] (8N1 is 10)");
            }
            requireProbability("bitFlipProbabilityPerByte", bitFlipProbabilityPerByte);
            requireProbability("dropProbabilityPerByte", dropProbabilityPerByte);
            if (receiveBufferBytes < DspProtocol.MAX_FRAME_BYTES) {
                throw new IllegalArgumentException("receiveBufferBytes=" + receiveBufferBytes
                        + ": must hold at least one frame (" + DspProtocol.MAX_FRAME_BYTES + ")");
            }
        }

        /**
         * 115200 baud 8N1, no faults, a 4 KiB receive buffer.
         *
         * @return the default settings, with seed 1
         */
        public static Config defaults() {
            return new Config(DEFAULT_BAUD_RATE, 10, 0.0, 0.0, 1L, 4096);
        }

        /**
         * A copy at another baud rate.
         *
         * @param bitsPerSecond the baud rate, within [50, 20000000]
         * @return the copy
         * @throws IllegalArgumentException when {@code bitsPerSecond} is out of range
         */
        public Config withBaudRate(int bitsPerSecond) {
            return new Config(bitsPerSecond, bitsPerByte, bitFlipProbabilityPerByte,
                    dropProbabilityPerByte, seed, receiveBufferBytes);
        }

        /**
         * A copy with fault injection.
         *
         * @param bitFlipPerByte chance that a byte arrives with one bit flipped, within [0, 1]
         * @param dropPerByte    chance that a byte is lost, within [0, 1]
         * @param randomSeed     the seed, so that a run with faults can be repeated
         * @return the copy
         * @throws IllegalArgumentException when a probability is out of range
         */
        public Config withFaults(double bitFlipPerByte, double dropPerByte, long randomSeed) {
            return new Config(baudRate, bitsPerByte, bitFlipPerByte, dropPerByte, randomSeed,
                    receiveBufferBytes);
        }

        /**
         * The time one byte takes on the wire.
         *
         * @return {@code bitsPerByte / baudRate}, in nanoseconds (about 86806 at 115200 baud 8N1)
         */
        public double byteTimeNs() {
            return bitsPerByte * 1e9 / baudRate;
        }

        private static void requireProbability(String field, double value) {
            if (!(value >= 0.0 && value <= 1.0)) {
                throw new IllegalArgumentException(field + "=" + value + ": must be within [0, 1]");
            }
        }
    }

    /**
     * What happened to the bytes sent one way. Immutable snapshot.
     *
     * @param bytesSent bytes written by the sender
     * @param bytesFlipped bytes delivered with one bit flipped
     * @param bytesDropped bytes lost on the wire
     * @param bytesOverrun bytes lost because the receiver's buffer was full
     */
    public record Counters(long bytesSent, long bytesFlipped, long bytesDropped, long bytesOverrun) {}

    private final Channel hostToBoard;
    private final Channel boardToHost;
    private final End hostEnd;
    private final End boardEnd;

    private SimulatedSerialLink(Config config, LockStepClock lockStepClock) {
        SplittableRandom seeds = new SplittableRandom(config.seed());
        this.hostToBoard = new Channel(config, seeds.split());
        this.boardToHost = new Channel(config, seeds.split());
        this.hostEnd = new End("simulated-host", boardToHost, hostToBoard, lockStepClock);
        this.boardEnd = new End("simulated-board", hostToBoard, boardToHost, lockStepClock);
        if (lockStepClock != null) {
            lockStepClock.register(new LockStepClock.Participant() {
                @Override
                public long nextEventNs(long nowNs) {
                    return Math.min(hostToBoard.nextArrivalAfter(nowNs),
                            boardToHost.nextArrivalAfter(nowNs));
                }

                @Override
                public void advanceTo(long nowNs) {
                    // Bytes become readable by their arrival time; nothing to do.
                }
            });
        }
    }

    /**
     * A cable in real time, on {@link System#nanoTime()}: a reader blocks until bytes arrive.
     *
     * @param config the cable's settings
     * @return the cable
     */
    public static SimulatedSerialLink realTime(Config config) {
        return new SimulatedSerialLink(config, null);
    }

    /**
     * A cable in the simulated time of a lock-step clock, which it registers with as a participant.
     *
     * @param config the cable's settings
     * @param clock  the clock; a reader's wait advances its time
     * @return the cable
     * @throws NullPointerException when {@code clock} is null
     */
    public static SimulatedSerialLink lockStep(Config config, LockStepClock clock) {
        return new SimulatedSerialLink(config, java.util.Objects.requireNonNull(clock, "clock"));
    }

    /**
     * The controller host's end.
     *
     * @return the end a {@link DspClient} uses
     */
    public SerialLink hostEnd() {
        return hostEnd;
    }

    /**
     * The DSP board's end.
     *
     * @return the end the simulated board uses
     */
    public SerialLink boardEnd() {
        return boardEnd;
    }

    /**
     * What happened to the bytes from host to board.
     *
     * @return a new snapshot
     */
    public Counters hostToBoardCounters() {
        return hostToBoard.counters();
    }

    /**
     * What happened to the bytes from board to host.
     *
     * @return a new snapshot
     */
    public Counters boardToHostCounters() {
        return boardToHost.counters();
    }

    /** One direction of the cable: a receive FIFO of bytes with their arrival times. */
    private static final class Channel {
        private final ReentrantLock lock = new ReentrantLock();
        private final Condition changed = lock.newCondition();
        private final double byteTimeNs;
        private final double flipProbability;
        private final double dropProbability;
        private final SplittableRandom random;
        private final byte[] data;
        private final long[] arrivalNs;
        private int head;
        private int size;
        private long transmitterFreeAtNs = Long.MIN_VALUE;
        private long sent;
        private long flipped;
        private long dropped;
        private long overrun;

        Channel(Config config, SplittableRandom random) {
            this.byteTimeNs = config.byteTimeNs();
            this.flipProbability = config.bitFlipProbabilityPerByte();
            this.dropProbability = config.dropProbabilityPerByte();
            this.random = random;
            this.data = new byte[config.receiveBufferBytes()];
            this.arrivalNs = new long[config.receiveBufferBytes()];
        }

        void transmit(byte[] bytes, int offset, int length, long nowNs) {
            lock.lock();
            try {
                long start = Math.max(nowNs, transmitterFreeAtNs);
                for (int i = 0; i < length; i++) {
                    long arrival = start + Math.round((i + 1) * byteTimeNs);
                    sent++;
                    // Draw both numbers for every byte so one fault never shifts the next ones.
                    double dropDraw = random.nextDouble();
                    double flipDraw = random.nextDouble();
                    int bit = random.nextInt(8);
                    if (dropDraw < dropProbability) {
                        dropped++;
                        continue;
                    }
                    byte value = bytes[offset + i];
                    if (flipDraw < flipProbability) {
                        value ^= (byte) (1 << bit);
                        flipped++;
                    }
                    if (size == data.length) {
                        overrun++;
                        continue;
                    }
                    int tail = (head + size) % data.length;
                    data[tail] = value;
                    arrivalNs[tail] = arrival;
                    size++;
                }
                transmitterFreeAtNs = start + Math.round(length * byteTimeNs);
                changed.signalAll();
            } finally {
                lock.unlock();
            }
        }

        /** Moves the bytes that have arrived by {@code nowNs} into {@code buffer}. */
        int takeArrived(byte[] buffer, int offset, int length, long nowNs) {
            lock.lock();
            try {
                int n = 0;
                while (n < length && size > 0 && arrivalNs[head] <= nowNs) {
                    buffer[offset + n++] = data[head];
                    head = (head + 1) % data.length;
                    size--;
                }
                return n;
            } finally {
                lock.unlock();
            }
        }

        boolean hasArrived(long nowNs) {
            lock.lock();
            try {
                return size > 0 && arrivalNs[head] <= nowNs;
            } finally {
                lock.unlock();
            }
        }

        long nextArrivalAfter(long nowNs) {
            lock.lock();
            try {
                for (int i = 0; i < size; i++) {
                    long arrival = arrivalNs[(head + i) % data.length];
                    if (arrival > nowNs) {
                        return arrival;
                    }
                }
                return Long.MAX_VALUE;
            } finally {
                lock.unlock();
            }
        }

        /** Real time: sleeps until a byte has arrived or the deadline passes. */
        int awaitAndTake(byte[] buffer, int offset, int length, long deadlineNs, End end)
                throws IOException {
            lock.lock();
            try {
                while (true) {
                    end.ensureOpen();
                    long now = System.nanoTime();
                    int n = takeArrived(buffer, offset, length, now);
                    if (n > 0 || now - deadlineNs >= 0) {
                        return n;
                    }
                    long wakeNs = size > 0 ? Math.min(arrivalNs[head], deadlineNs) : deadlineNs;
                    changed.awaitNanos(Math.max(1L, wakeNs - now));
                }
            } catch (InterruptedException e) {
                Thread.currentThread().interrupt();
                throw new InterruptedIOException("interrupted while reading " + end.name);
            } finally {
                lock.unlock();
            }
        }

        void wakeReaders() {
            lock.lock();
            try {
                changed.signalAll();
            } finally {
                lock.unlock();
            }
        }

        Counters counters() {
            lock.lock();
            try {
                return new Counters(sent, flipped, dropped, overrun);
            } finally {
                lock.unlock();
            }
        }
    }

    /** One end: reads its inbound channel, writes the outbound one. */
    private static final class End implements SerialLink {
        private final String name;
        private final Channel inbound;
        private final Channel outbound;
        private final LockStepClock lockStepClock;
        private volatile boolean closed;

        End(String name, Channel inbound, Channel outbound, LockStepClock lockStepClock) {
            this.name = name;
            this.inbound = inbound;
            this.outbound = outbound;
            this.lockStepClock = lockStepClock;
        }

        @Override
        public String name() {
            return name;
        }

        private long nowNs() {
            return lockStepClock != null ? lockStepClock.nanoTime() : System.nanoTime();
        }

        @Override
        public void write(byte[] bytes, int offset, int length) throws IOException {
            ensureOpen();
            outbound.transmit(bytes, offset, length, nowNs());
        }

        @Override
        public int read(byte[] buffer, int offset, int length, long timeoutNs) throws IOException {
            ensureOpen();
            if (timeoutNs < 0) {
                throw new IllegalArgumentException("timeoutNs=" + timeoutNs + ": must be >= 0");
            }
            long now = nowNs();
            int n = inbound.takeArrived(buffer, offset, length, now);
            if (n > 0 || timeoutNs == 0) {
                return n;
            }
            long deadline = now + timeoutNs;
            if (lockStepClock == null) {
                return inbound.awaitAndTake(buffer, offset, length, deadline, this);
            }
            lockStepClock.advanceUntil(() -> closed || inbound.hasArrived(lockStepClock.nanoTime()),
                    deadline);
            ensureOpen();
            return inbound.takeArrived(buffer, offset, length, lockStepClock.nanoTime());
        }

        void ensureOpen() throws IOException {
            if (closed) {
                throw new IOException(name + " is closed");
            }
        }

        @Override
        public void close() {
            closed = true;
            inbound.wakeReaders();
        }

        @Override
        public String toString() {
            return name;
        }
    }
}
