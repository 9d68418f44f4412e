package io.etherware.deploy.view;

import java.lang.invoke.MethodHandles;
import java.lang.invoke.VarHandle;
import java.util.List;
import java.util.Objects;
import java.util.concurrent.CopyOnWriteArrayList;
import java.util.regex.Pattern;

/**
 * A node's live signals: named numeric time series that its components publish (a controller's
 * angles and torque, say) and its {@link NodeView} plots and exports, each kept in a bounded ring
 * of its last {@link #capacity()} samples. A {@link io.etherware.deploy.ComponentFactory} gets the
 * node's from its resources and creates its signals once, in {@code create}; the component then
 * {@link Signal#record records} into them on its dispatcher.
 *
 * <p>Thread-safe. Creating a signal allocates and takes a lock; recording neither allocates nor
 * locks nor blocks (two plain array stores and one release store), and readers never hold the
 * writer up: a reader that loses a race with the writer drops the samples it may have seen half
 * written.
 */
public final class LiveSignals {

    /** Samples kept per signal by default: 30 s of a 15 ms loop. */
    public static final int DEFAULT_CAPACITY = 2_000;

    private static final Pattern NAME = Pattern.compile("[A-Za-z_][A-Za-z0-9_.\\-]{0,63}");
    private static final Pattern UNIT = Pattern.compile("[A-Za-z0-9_.·/%\\-]{0,16}");

    private final int capacity;
    private final List<Signal> signals = new CopyOnWriteArrayList<>();

    /** A registry keeping {@link #DEFAULT_CAPACITY} samples per signal. */
    public LiveSignals() {
        this(DEFAULT_CAPACITY);
    }

    /**
     * A registry keeping {@code capacity} samples per signal.
     *
     * @param capacity samples kept per signal, 1..1,000,000
     */
    public LiveSignals(int capacity) {
        if (capacity < 1 || capacity > 1_000_000) {
            throw new IllegalArgumentException("capacity=" + capacity + ": keep 1..1000000 samples per signal");
        }
        this.capacity = capacity;
    }

    /** {@return how many samples each signal keeps} */
    public int capacity() {
        return capacity;
    }

    /**
     * Creates the signal {@code name}. Call it once per signal, when the component is configured
     * (not per message).
     *
     * @param name a name unique in this node: a letter or {@code _}, then letters, digits,
     *             {@code _ . -}, at most 64 characters (e.g. {@code theta1})
     * @param unit its unit as people write it, e.g. {@code rad}, {@code N·m}, {@code ms}; may be empty
     * @return the signal, to record into
     * @throws IllegalArgumentException for a bad name or unit, or a name already taken
     */
    public synchronized Signal create(String name, String unit) {
        Objects.requireNonNull(name, "name");
        Objects.requireNonNull(unit, "unit");
        if (!NAME.matcher(name).matches()) {
            throw new IllegalArgumentException("signal name=\"" + name + "\": use a letter or '_', then letters,"
                    + " digits, '_', '.', '-', at most 64 characters");
        }
        if (!UNIT.matcher(unit).matches()) {
            throw new IllegalArgumentException("signal " + name + " unit=\"" + unit + "\": use at most 16 letters,"
                    + " digits or '_ . · / % -', e.g. rad or N·m");
        }
        for (Signal existing : signals) {
            if (existing.name.equals(name)) {
                throw new IllegalArgumentException("signal name=\"" + name + "\" is already published on this node;"
                        + " give each signal its own name");
            }
        }
        var signal = new Signal(name, unit, capacity);
        signals.add(signal);
        return signal;
    }

    /** {@return every signal, in the order they were created} */
    public List<Signal> signals() {
        return List.copyOf(signals);
    }

    /**
     * One named series: a ring of the last samples, each a time (nanoseconds on any monotonic
     * clock the writer chooses, the same for every sample) and a value ({@code NaN} for "no value
     * this time").
     *
     * <p>One writer at a time: the component that records into it (the kernel never runs a
     * component on two threads at once). Any number of readers.
     */
    public static final class Signal {

        private static final VarHandle WRITTEN;

        static {
            try {
                WRITTEN = MethodHandles.lookup().findVarHandle(Signal.class, "written", long.class);
            } catch (ReflectiveOperationException e) {
                throw new ExceptionInInitializerError(e);
            }
        }

        private final String name;
        private final String unit;
        private final int capacity;
        /** One slot more than the samples kept: the one the writer may be filling now. */
        private final long[] timesNs;
        private final double[] values;
        /** Samples recorded so far; sample {@code s} is at slot {@code s % (capacity + 1)}. */
        @SuppressWarnings("unused") // through WRITTEN
        private volatile long written;

        private Signal(String name, String unit, int capacity) {
            this.name = name;
            this.unit = unit;
            this.capacity = capacity;
            timesNs = new long[capacity + 1];
            values = new double[capacity + 1];
        }

        /** {@return the signal's name} */
        public String name() {
            return name;
        }

        /** {@return its unit, possibly empty} */
        public String unit() {
            return unit;
        }

        /**
         * Records one sample. Called by the signal's one writer; allocation-free, never blocks.
         *
         * @param timeNs when, in nanoseconds on the writer's monotonic clock
         * @param value  the value, or {@code NaN} for none
         */
        public void record(long timeNs, double value) {
            long sample = (long) WRITTEN.getOpaque(this);
            int slot = (int) (sample % timesNs.length);
            timesNs[slot] = timeNs;
            values[slot] = value;
            WRITTEN.setRelease(this, sample + 1);
        }

        /** {@return how many samples were recorded since the signal was created} */
        public long recorded() {
            return (long) WRITTEN.getAcquire(this);
        }

        /**
         * The samples still kept, oldest first, copied at one moment.
         *
         * @return the samples; empty before the first
         */
        public Samples samples() {
            long before = (long) WRITTEN.getAcquire(this);
            int slots = timesNs.length;
            long first = Math.max(0, before - capacity);
            int count = (int) (before - first);
            long[] times = new long[count];
            double[] copied = new double[count];
            for (int i = 0; i < count; i++) {
                int slot = (int) ((first + i) % slots);
                times[i] = timesNs[slot];
                copied[i] = values[slot];
            }
            // Meanwhile the writer may have written samples up to `after` - 1 and be writing sample
            // `after`, each into the slot of the sample `slots` before it: keep only samples it
            // cannot have touched. A writer that did not move costs nothing (the spare slot).
            long after = (long) WRITTEN.getAcquire(this);
            long firstSafe = Math.max(first, after + 1 - slots);
            int skip = (int) Math.min(count, firstSafe - first);
            if (skip == 0) {
                return new Samples(times, copied);
            }
            return new Samples(java.util.Arrays.copyOfRange(times, skip, count),
                    java.util.Arrays.copyOfRange(copied, skip, count));
        }

        @Override
        public String toString() {
            return "signal " + name + (unit.isEmpty() ? "" : " [" + unit + "]");
        }
    }

    /**
     * A copy of a signal's samples, oldest first; the two arrays have the same length. Owned by
     * the caller.
     *
     * @param timesNs when, on the writer's clock
     * @param values  the values ({@code NaN}: none)
     */
    public record Samples(long[] timesNs, double[] values) {

        /** {@return how many samples} */
        public int size() {
            return timesNs.length;
        }
    }
}
